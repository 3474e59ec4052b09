#!/usr/bin/python3
"""The command line on invalid input (INTERFACE.md): `grainflow run` and `grainflow check` exit with
status 2, the message names the file, the key and the reason, and nothing is written (the output
folder is not created). Also --version, `cases` and `check` on the bundled demo, whose printed
derived quantities are recomputed here from the case file (Lan 1994 eqs. 2-5-4, 4-1-3).

Usage: /usr/bin/python3 tests/integration/test_cli_input_errors.py PATH_TO_grainflow  (from the repo root)
"""
import math
import os
import re
import sys
import tempfile
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gftest import check, executable_from_argv, finish, run, write_text  # noqa: E402

# A valid case: 20 glass spheres (d = 3 mm) in a periodic box with a floor. Each bad case breaks one key.
VALID = """[engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 20

[contact]
k1 = 1.0e6
restitution = 0.9

[run]
duration = 0.001

[output]
interval = 0.0005
"""

# (name, case text, key the message must name, words of the reason)
BAD_CASES = [
    ("unknown_key", VALID.replace("k1 = 1.0e6", "k1 = 1.0e6\nk11 = 2.0"), "contact.k11", "unknown key"),
    ("wrong_type", VALID.replace("diameter = 0.003", 'diameter = "3 mm"'), "species.0.diameter", "expected a number"),
    ("missing_required", VALID.replace("duration = 0.001", ""), "run.duration", "required"),
    ("restitution_out_of_range", VALID.replace("restitution = 0.9", "restitution = 1.5"), "contact.restitution", "(0, 1]"),
    ("negative_density", VALID.replace("density = 2490.0", "density = -2490.0"), "species.0.density", "positive"),
    ("too_many_particles", VALID.replace("count = 20", "count = 2000"), "species.count", "placement region"),
    ("time_step_too_large", VALID.replace("duration = 0.001", "duration = 0.001\ntime_step = 1e-4"), "run.time_step",
     "steps"),
    ("drive_on_periodic_face", VALID + '\n[drive]\nface = "xlo"\namplitude = [0.001, 0.0, 0.0]\n'
     'frequency = [20.0, 0.0, 0.0]\n', "drive.face", "periodic"),
    ("averaging_window_in_collisions_with_dem", VALID + "average_start_collisions = 1000\n",
     "output.average_start_collisions", "event-driven"),
    ("trajectory_too_few_samples", VALID + "\n[trajectory]\nsamples = 1\n", "trajectory.samples", "at least 2"),
    ("trajectory_unknown_particle", VALID + "\n[trajectory]\nparticles = [3, 20]\n", "trajectory.particles",
     "no particle with id 20"),
    ("trajectory_lag_beyond_samples", VALID + "\n[trajectory]\nsamples = 100\nmax_lag = 100\n", "trajectory.max_lag",
     "[0, samples)"),
    ("zone_series_without_drive_or_interval", VALID + "\n[zone_series]\nsamples = 64\n", "zone_series.interval",
     "needs a value"),
]


def main():
    exe = executable_from_argv(__doc__)
    if exe is None:
        return 2
    check(os.access(exe, os.X_OK), f"{exe} is not an executable")
    os.chdir(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))  # the repo root

    with tempfile.TemporaryDirectory(prefix="grainflow_cli_") as tmp:
        # The valid case runs (sanity: the bad cases fail for their one broken key, not for the rest).
        valid_path = write_text(os.path.join(tmp, "valid.toml"), VALID)
        status, _, err = run(exe, "check", valid_path)
        check(status == 0, f"check of the valid case exited {status}: {err.strip()}")
        status, _, err = run(exe, "run", valid_path, "-o", os.path.join(tmp, "valid_out"), "--quiet")
        check(status == 0, f"run of the valid case exited {status}: {err.strip()}")
        check(os.path.isfile(os.path.join(tmp, "valid_out", "summary.json")), "the valid run wrote no summary.json")

        for name, text, key, reason in BAD_CASES:
            path = write_text(os.path.join(tmp, name + ".toml"), text)
            for command in ("run", "check"):
                out_dir = os.path.join(tmp, "out_" + name)
                args = [command, path] + (["-o", out_dir] if command == "run" else [])
                status, _, err = run(exe, *args)
                check(status == 2, f"{name}: `grainflow {command}` exited {status}, expected 2 (stderr: {err.strip()})")
                check(path in err, f"{name}: `grainflow {command}` stderr does not name the file {path}: {err.strip()}")
                check(key in err, f"{name}: `grainflow {command}` stderr does not name the key {key}: {err.strip()}")
                check(reason in err, f"{name}: `grainflow {command}` stderr lacks the reason '{reason}': {err.strip()}")
                check(not os.path.exists(out_dir), f"{name}: `grainflow {command}` created the output folder {out_dir}")

        # Without -o the default folder is runs/<case name> under the working directory: not created either.
        default_name = f"bad_default_{os.getpid()}"
        path = write_text(os.path.join(tmp, default_name + ".toml"), BAD_CASES[0][1])
        status, _, _ = run(exe, "run", path, cwd=tmp)
        check(status == 2, f"bad case without -o exited {status}, expected 2")
        check(not os.path.exists(os.path.join(tmp, "runs", default_name)), "a bad case created runs/<case name>")
        check(not os.path.exists(os.path.join(tmp, "runs")), "a bad case created runs/")

        # TOML syntax error: the message names the file and the line of "k1 = = 1.0e6".
        broken = VALID.replace("k1 = 1.0e6", "k1 = = 1.0e6")
        line = broken[: broken.index("k1 = =")].count("\n") + 1
        path = write_text(os.path.join(tmp, "syntax.toml"), broken)
        out_dir = os.path.join(tmp, "out_syntax")
        status, _, err = run(exe, "run", path, "-o", out_dir)
        check(status == 2, f"syntax error: exited {status}, expected 2")
        check(path in err and f"line {line}" in err, f"syntax error: stderr should name {path} and line {line}: {err.strip()}")
        check(not os.path.exists(out_dir), "syntax error: the output folder was created")

        # --set with a key that does not exist, a bad value, and a bad index: exit 2, message mentions --set.
        for assignment, key in (("contact.k11=2e6", "contact.k11"), ("contact.k1=-1", "contact.k1"),
                                ("species.5.count=3", "species.5.count")):
            for command in ("run", "check"):
                out_dir = os.path.join(tmp, "out_set")
                args = [command, valid_path, "--set", assignment] + (["-o", out_dir] if command == "run" else [])
                status, _, err = run(exe, *args)
                check(status == 2, f"--set {assignment}: `grainflow {command}` exited {status}, expected 2")
                check("--set" in err and key in err and valid_path in err,
                      f"--set {assignment}: stderr should mention --set, {key} and {valid_path}: {err.strip()}")
                check(not os.path.exists(out_dir), f"--set {assignment}: the output folder was created")
        # A valid --set is applied: check prints the overridden stiffness.
        status, out, err = run(exe, "check", valid_path, "--set", "contact.k1=2.5e6")
        check(status == 0 and re.search(r"K1 \(loading\)\s+2\.5e\+06 N/m", out) is not None,
              f"--set contact.k1=2.5e6 not reflected by check (status {status}): {out}{err}")

        # A missing case file, an unknown subcommand: invalid input too.
        status, _, err = run(exe, "check", os.path.join(tmp, "no_such_case.toml"))
        check(status == 2 and "no_such_case.toml" in err, f"missing case file: exited {status}: {err.strip()}")
        status, _, _ = run(exe, "frobnicate")
        check(status == 2, f"unknown subcommand exited {status}, expected 2")

        # A particle file that is a device (it would never end): refused before reading, exit 2.
        device = VALID.replace("count = 20", "count = 0") + '\n[particles]\ninit = "file"\nfile = "/dev/zero"\n'
        path = write_text(os.path.join(tmp, "device.toml"), device.replace("[output]", "[output]", 1))
        out_dir = os.path.join(tmp, "out_device")
        status, _, err = run(exe, "run", path, "-o", out_dir)
        check(status == 2 and "/dev/zero" in err and "not a regular file" in err,
              f"particles.file = /dev/zero: exited {status}: {err.strip()}")
        check(not os.path.exists(out_dir), "particles.file = /dev/zero: the output folder was created")

        # A huge, nearly empty box (20 spheres in a 1 km cube) is legal: it runs, with a grid sized by
        # the particles rather than the volume (it used to die of std::bad_alloc).
        huge = VALID.replace("hi = [0.02, 0.05, 0.02]", "hi = [1000.0, 1000.0, 1000.0]")
        path = write_text(os.path.join(tmp, "huge_box.toml"), huge)
        status, _, err = run(exe, "run", path, "-o", os.path.join(tmp, "out_huge"), "--quiet")
        check(status == 0, f"a 1 km box with 20 spheres: exited {status}: {err.strip()}")

    # --version
    status, out, err = run(exe, "--version")
    check(status == 0 and re.match(r"grainflow \d+\.\d+\.\d+", out.strip()) is not None,
          f"--version: status {status}, output {out!r} {err!r}")

    # cases lists the demo
    status, out, err = run(exe, "cases")
    check(status == 0, f"`grainflow cases` exited {status}: {err}")
    check("cases/demo/vibrated_bed.toml" in out, f"`grainflow cases` does not list cases/demo/vibrated_bed.toml:\n{out}")

    # check on the demo: exit 0, and the derived quantities it prints agree with the case file.
    demo = "cases/demo/vibrated_bed.toml"
    status, out, err = run(exe, "check", demo)
    check(status == 0, f"`grainflow check {demo}` exited {status}: {err}")
    with open(demo, "rb") as f:
        case = tomllib.load(f)
    species = case["species"][0]
    d, rho, count = species["diameter"], species["density"], species["count"]
    k1, e = case["contact"]["k1"], case["contact"]["restitution"]
    n = case["run"].get("collision_steps", 15)
    mass = math.pi / 6.0 * d ** 3 * rho
    expected = {
        # eq. (2-5-4)
        "time step": math.pi * e / n * math.sqrt(mass / (2.0 * k1)),
        # eq. (4-1-3): N pi d^2 / (6 A) over the x-z cross-section
        "mass hold-up m_t": count * math.pi * d ** 2 / (6.0 * (case["domain"]["hi"][0] - case["domain"]["lo"][0]) *
                                                       (case["domain"]["hi"][2] - case["domain"]["lo"][2])),
        # Gamma = a (2 pi f)^2 / g
        "shaking acceleration Gamma": case["drive"]["amplitude"][1] * (2 * math.pi * case["drive"]["frequency"][1]) ** 2
        / 9.81,
    }
    for label, value in expected.items():
        match = re.search(re.escape(label) + r"\s+([-+0-9.eE]+)", out)
        check(match is not None, f"check output lacks '{label}':\n{out}")
        if match:
            printed = float(match.group(1))
            # printed with 6 significant digits: 1e-5 relative covers its rounding
            check(abs(printed - value) <= 1e-5 * abs(value), f"check prints {label} = {printed}, expected {value:.6g}")

    return finish("test_cli_input_errors")


if __name__ == "__main__":
    sys.exit(main())
