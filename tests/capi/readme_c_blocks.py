"""The ```c blocks of README.md, compiled and run against the built library: the first is a whole
program; the others are fragments of a host's code, each compiled into a function that gets a
world with a stepped ball and a jelly on the ground (`world`, `jelly`) and run.

  readme_c_blocks.py REPO_ROOT LIBRARY_DIR C_COMPILER [EXTRA_FLAGS]
"""
import os
import re
import subprocess
import sys
import tempfile

PRELUDE = r"""
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include "volphys/volphys.h"

static void fragment(vpWorldId world, vpDeformableId jelly);

int main(void) {
  vpWorldDef def = vpDefaultWorldDef();
  vpColliderDef ground = vpDefaultColliderDef(), ball = vpDefaultColliderDef();
  vpDeformableDef box = vpDefaultDeformableDef();
  vpWorldId world;
  vpColliderId id;
  vpDeformableId jelly;
  static float vertices[3 * 27];
  static int32_t tets[4 * 48];
  const int32_t cells[3] = {2, 2, 2};
  vpVec3 size = {0.4f, 0.4f, 0.4f}, corner = {1.0f, 0.0f, -0.2f};
  int32_t nv = 0, nt = 0;
  def.frameBudgetMs = 0.0f;
  if (vpWorldCreate(&def, &world) != vpStatus_Ok) return 10;
  ground.shape.type = vpShapeType_Plane;
  ball.bodyType = vpBodyType_Dynamic;
  ball.pose.position.y = 2.0f;
  if (vpColliderCreate(world, &ground, &id) != vpStatus_Ok || vpColliderCreate(world, &ball, &id) != vpStatus_Ok) return 11;
  if (vpBoxTetMesh(size, cells, corner, vertices, 27, tets, 48, &nv, &nt) != vpStatus_Ok) return 12;
  box.degree = 2;
  box.vertices = vertices;
  box.vertexCount = nv;
  box.tets = tets;
  box.tetCount = nt;
  if (vpDeformableCreate(world, &box, &jelly) != vpStatus_Ok) return 13;
  vpWorldStep(world, 1.0f / 60.0f);
  fragment(world, jelly);
  vpWorldDestroy(world);
  printf("fragment ran\n");
  return 0;
}

static void fragment(vpWorldId world, vpDeformableId jelly) {
  (void)world;
  (void)jelly;
"""


def c_blocks(text):
    return [m.group(1) for m in re.finditer(r"^```c\n(.*?)^```", text, re.S | re.M)]


def build_and_run(source, root, libdir, cc, flags, work, name):
    path = os.path.join(work, name + ".c")
    with open(path, "w") as f:
        f.write(source)
    exe = os.path.join(work, name)
    command = [cc, "-std=c99", "-pedantic-errors", "-Wall", "-Werror", path, "-I", os.path.join(root, "plugin_api", "include"),
               "-L", libdir, "-lvolphys", "-Wl,-rpath," + libdir, "-o", exe] + flags
    r = subprocess.run(command, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("%s does not compile:\n%s\n%s" % (name, source, r.stderr))
    r = subprocess.run([exe], capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        sys.exit("%s exited with %d:\n%s%s" % (name, r.returncode, r.stdout, r.stderr))


def main():
    root, libdir, cc = sys.argv[1:4]
    flags = sys.argv[4].split() if len(sys.argv) > 4 else []
    with open(os.path.join(root, "README.md"), encoding="utf-8") as f:
        blocks = c_blocks(f.read())
    if len(blocks) < 2:
        sys.exit("README.md: expected a program and fragments in ```c blocks, found %d" % len(blocks))
    with tempfile.TemporaryDirectory(prefix="volphys-readme-c-") as work:
        build_and_run(blocks[0], root, libdir, cc, flags, work, "program")
        for i, block in enumerate(blocks[1:], 1):
            build_and_run(PRELUDE + block + "}\n", root, libdir, cc, flags, work, "fragment%d" % i)
    print("README C blocks ran: 1 program, %d fragments" % (len(blocks) - 1))


if __name__ == "__main__":
    main()
