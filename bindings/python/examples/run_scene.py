#!/usr/bin/env python3
"""Runs a VolPhys scene file for N frames and prints per-frame step statistics.

    VOLPHYS_LIBRARY=build/release/plugin_api/libvolphys.so PYTHONPATH=bindings/python \
        /usr/bin/python3 bindings/python/examples/run_scene.py sample_host/scenes/default.json \
        --frames 120 --plot frame_times.png

With matplotlib importable, --plot writes frame time against the budget to a PNG; without
it the plot is skipped with a note (everything else works).
"""
import argparse
import sys

import volphys


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", help="JSON scene file")
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--dt", type=float, default=1.0 / 60.0)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--budget-ms", type=float, default=None,
                    help="frame budget in ms (default: the scene's, else the library's)")
    ap.add_argument("--plot", metavar="PNG", default=None, help="write a frame-time plot here")
    args = ap.parse_args(argv)

    frames = []
    try:
        with volphys.World(workers=args.workers) as world:
            world.load_scene(args.scene)
            # Set after loading: the scene's "world" block may set its own budget.
            if args.budget_ms is not None:
                world.set_frame_budget(args.budget_ms)
            print("frame  total_ms budget_ms cut actors colliders substeps")
            for _ in range(args.frames):
                s = world.step(args.dt)
                frames.append(s)
                print("%5d %9.3f %9.3f %3d %6d %9d %8d" % (s.step_index, s.total_ms, s.budget_ms, s.budget_cut,
                                                           s.actor_count, s.collider_count, s.rigid_substeps))
    except volphys.VolPhysError as e:
        print("error: %s" % e, file=sys.stderr)
        return 1

    if frames:
        times = sorted(s.total_ms for s in frames)
        print("summary: %d frames, median %.3f ms, max %.3f ms, %d budget cuts"
              % (len(frames), times[len(times) // 2], times[-1], sum(s.budget_cut for s in frames)))
    if args.plot:
        write_plot(frames, args.plot)
    return 0


def write_plot(frames, path):
    try:
        import matplotlib
        matplotlib.use("Agg")  # headless: no display needed
        import matplotlib.pyplot as plt
    except ImportError:
        print("note: matplotlib is not importable; no plot written", file=sys.stderr)
        return
    x = [s.step_index for s in frames]
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(x, [s.total_ms for s in frames], label="step time")
    ax.plot(x, [s.budget_ms for s in frames], "--", label="budget (0 = unlimited)")
    ax.set_xlabel("frame")
    ax.set_ylabel("ms")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print("plot: %s" % path)


if __name__ == "__main__":
    sys.exit(main())
