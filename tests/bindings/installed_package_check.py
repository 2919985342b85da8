"""Installs the Python package the ways a user would and runs a world from the install alone
(a child interpreter in a temporary folder, with only the install on PYTHONPATH).

  installed_package_check.py pip SOURCE_DIR LIBRARY      pip install --target; $VOLPHYS_LIBRARY
  installed_package_check.py bundled SOURCE_DIR LIBRARY  the library copied into the package
                                                          before pip install; no $VOLPHYS_LIBRARY
  installed_package_check.py cmake BUILD_DIR             cmake --install into a prefix; the
                                                          package finds the library of that prefix

pip builds in the folder it installs from, so it installs from a copy of bindings/python.
"""
import glob
import os
import shutil
import subprocess
import sys
import tempfile

# Creates a world, steps it, and prints where the package and the library came from.
CHILD = r"""
import importlib.metadata, sys, volphys
vertices, tets = volphys.box_tet_mesh((0.4, 0.2, 0.2), (2, 1, 1), min_corner=(-0.2, 0.5, -0.1))
with volphys.World() as world:
    world.create_collider(volphys.Plane())
    ball = world.create_collider(volphys.Sphere(0.25), position=(1, 1, 0))
    block = world.create_deformable(vertices=vertices, tets=tets)
    for _ in range(60):
        stats = world.step(1 / 60)
    assert stats.step_index == 60, stats
    assert 0.2 < ball.position[1] < 0.3, ball.position
    assert block.node_count == 12
if sys.argv[1:] == ["--pip"]:  # pip records the pyproject's version; it must be the library's
    assert importlib.metadata.version("volphys") == volphys.__version__, importlib.metadata.version("volphys")
print("package", volphys.__file__)
print("library", volphys.library_path())
"""


def run(command, **kwargs):
    r = subprocess.run(command, capture_output=True, text=True, timeout=300, **kwargs)
    if r.returncode != 0:
        sys.exit("%s failed (%d):\n%s\n%s" % (" ".join(command), r.returncode, r.stdout, r.stderr))
    return r.stdout


def pip_install(source_dir, work, bundle_library=None):
    source = os.path.join(work, "src")
    shutil.copytree(os.path.join(source_dir, "bindings", "python"), source,
                    ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__", "libvolphys.so*"))
    if bundle_library:
        shutil.copy(bundle_library, os.path.join(source, "volphys", "libvolphys.so.0"))
    target = os.path.join(work, "site")
    run([sys.executable, "-m", "pip", "install", "--quiet", "--no-build-isolation", "--no-deps", "--no-index",
         "--target", target, source])
    return target


def check_child(work, site, env_extra, expect_package_in, expect_library, pip):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VOLPHYS_LIBRARY", "LD_LIBRARY_PATH")}
    env.update(env_extra, PYTHONPATH=site)
    out = run([sys.executable, "-c", CHILD] + (["--pip"] if pip else []), cwd=work, env=env)
    lines = dict(line.split(" ", 1) for line in out.splitlines() if " " in line)
    package, library = lines.get("package", ""), lines.get("library", "")
    if not os.path.realpath(package).startswith(os.path.realpath(expect_package_in) + os.sep):
        sys.exit("volphys was imported from %s, not from the install in %s" % (package, expect_package_in))
    if os.path.realpath(library) != os.path.realpath(expect_library):
        sys.exit("the library loaded was %s, expected %s" % (library, expect_library))
    print("installed package ran: %s with %s" % (package, library))


def main():
    mode = sys.argv[1]
    with tempfile.TemporaryDirectory(prefix="volphys-install-") as work:
        if mode == "pip":
            source_dir, library = sys.argv[2:4]
            site = pip_install(source_dir, work)
            check_child(work, site, {"VOLPHYS_LIBRARY": library}, site, library, pip=True)
        elif mode == "bundled":
            source_dir, library = sys.argv[2:4]
            site = pip_install(source_dir, work, bundle_library=library)
            check_child(work, site, {}, site, os.path.join(site, "volphys", "libvolphys.so.0"), pip=True)
        elif mode == "cmake":
            prefix = os.path.join(work, "prefix")
            run(["cmake", "--install", sys.argv[2], "--prefix", prefix])
            sites = glob.glob(os.path.join(prefix, "lib", "python3*", "dist-packages"))
            if len(sites) != 1:
                sys.exit("cmake --install: expected one lib/python3*/dist-packages, found %s" % sites)
            site = sites[0]
            check_child(work, site, {}, site, os.path.join(prefix, "lib", "libvolphys.so.0"), pip=False)
        else:
            sys.exit("unknown mode %r: expected pip, bundled or cmake" % mode)


if __name__ == "__main__":
    main()
