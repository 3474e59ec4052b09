#!/usr/bin/python3
"""Writes the soft-disc (DEM) twin of one of Campbell's event-driven cases, for comparing soft and
hard discs (docs/validation/campbell1982.md, "Soft discs on the same chute" and "in the
pressure-controlled Couette cell").

Campbell's discs are fully rough (every collision ends with no relative tangential velocity at the
contact) with constant restitutions e_p between discs and e_w at rough walls. Their soft twin, for a
normal stiffness kn (R = m = 1 units of the thesis): a linear spring-dashpot whose gamma_n gives e_p
for a pair (m_eff = 1/2) and e_w at a wall (m_eff = 1) exactly, no tangential damping, friction
1000 (no sliding), and kt = (kn / 12) (omega_d / omega_0)^2, which makes the tangential spring of a
disc pair (tangential effective mass m_eff / 3) end a quarter period as the contact does: its
tangential restitution is 0, Campbell's rough rule (the wall's within 0.02). A `[servo]` is kept
with `scale_width = false` (the DEM servo moves the walls only) and `interval = 1` (a time trigger:
contacts begun by soft discs are not the clock that hard collisions are); stresses are switched on.

Usage: /usr/bin/python3 tools/campbell_soft_discs.py CASE.toml KN > SOFT.toml
"""
import math
import re
import sys


def dashpot_damping(restitution, effective_mass, kn):
    """gamma_n of F = -kn x - m_eff gamma_n v that gives `restitution`: e = exp(-gamma pi / (2 omega_d))."""
    log_e = math.log(restitution)
    return 2.0 * math.sqrt(kn / effective_mass) * (-log_e) / math.sqrt(math.pi**2 + log_e**2)


def rough_tangential_stiffness(kn, pair_damping):
    """kt for tangential restitution 0 between two unit-mass discs: a quarter tangential period per contact."""
    omega0_squared = kn / 0.5
    return kn / 12.0 * (omega0_squared - pair_damping**2 / 4.0) / omega0_squared


def tables(text):
    """The case's tables as (header, body) in order, the text before the first header as ('', body)."""
    parts = re.split(r"(?m)^(\[[^\]\n]+\]\]?)[ \t]*(?:#.*)?$", text)
    out = [("", parts[0])]
    for k in range(1, len(parts), 2):
        out.append((parts[k].strip(), parts[k + 1]))
    return out


def number(body, key, where):
    found = re.search(rf"(?m)^[ \t]*{key}\s*=\s*([-+0-9.eE]+)", body)
    if not found:
        raise SystemExit(f"campbell_soft_discs: {where} has no numeric '{key}'")
    return float(found.group(1))


def soft_disc_case(text, kn):
    """The DEM twin of the event-driven case `text` at normal stiffness `kn`."""
    sections = tables(text)
    collision = next((body for header, body in sections if header == "[collision]"), None)
    if collision is None or not re.search(r'(?m)^[ \t]*roughness\s*=\s*"rough"', collision):
        raise SystemExit("campbell_soft_discs: the case needs a [collision] table with roughness = \"rough\"")
    if re.search(r"(?m)^[ \t]*restitution_law\s*=", collision):
        raise SystemExit("campbell_soft_discs: a velocity-dependent restitution has no constant-damping twin")
    pair_damping = dashpot_damping(number(collision, "restitution", "[collision]"), 0.5, kn)
    kt = rough_tangential_stiffness(kn, pair_damping)
    out = []
    for header, body in sections:
        if header == "[engine]":
            body = re.sub(r'(?m)^(\s*kind\s*=\s*)"edmd"', r'\1"dem"', body)
        elif header == "[collision]":
            header = "[contact]"
            body = (f'\nmodel = "linear_dashpot"\nkn = {kn!r}\nkt = {kt!r}\ngamma_n = {pair_damping!r}\n'
                    f"gamma_t = 0.0\nfriction = 1000.0                  # no sliding: fully rough\n\n")
        elif header.startswith("[walls."):
            if not re.search(r'(?m)^[ \t]*condition\s*=\s*"rough"', body):
                raise SystemExit(f"campbell_soft_discs: {header} is not a rough wall")
            wall_damping = dashpot_damping(number(body, "restitution", header), 1.0, kn)
            body = re.sub(r"(?m)^[ \t]*restitution\s*=.*$", f"gamma_n = {wall_damping!r}", body)
            body = re.sub(r"(?m)^[ \t]*condition\s*=.*$", "friction = 1000.0", body)
        elif header == "[servo]":
            body = re.sub(r"(?m)^[ \t]*scale_width\s*=.*\n?", "", body)
            body = re.sub(r"(?m)^[ \t]*interval\s*=.*\n?", "", body)
            body = "\nscale_width = false\ninterval = 1.0\n" + body.lstrip("\n")
        elif header == "[output]":
            body = re.sub(r"(?m)^[ \t]*collision_stresses\s*=.*\n?", "", body)
            body = "\nstresses = true\n" + body.lstrip("\n")
        out.append(header + body if header else body)
    note = (f"# Soft-disc twin (tools/campbell_soft_discs.py, kn = {kn!r}): linear spring-dashpot, "
            "restitutions exact, tangential restitution 0.\n")
    return note + "".join(out)


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    with open(sys.argv[1]) as f:
        sys.stdout.write(soft_disc_case(f.read(), float(sys.argv[2])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
