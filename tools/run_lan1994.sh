#!/bin/bash
# Runs every study of Lan 1994 (cases/lan1994) at full length into runs/lan1994/, then analyze,
# theory and plot (tools/run_thesis_cases.sh); docs/validation/lan1994.md compares the results with
# the thesis. About 1 h 40 min on 2 cores.
# Usage: tools/run_lan1994.sh [STUDY...]   (default: all, cheapest first; e.g. `tools/run_lan1994.sh table4_3_hunt`)
# Environment: GRAINFLOW (default build/release/grainflow), GRAINFLOW_JOBS (parallel sweep runs, default 2).
ALL="table4_5_diffusion_gamma90 table4_5_diffusion_gamma483 table4_6_diffusion_amplitude_half_d
table4_7_diffusion_amplitude_001d sec4_3_spectra table5_1_convection_amplitude table5_2_friction
sec5_1_3_cell_20dx3d sec5_1_3_cell_100dx1d sec5_2_large_sphere_6dx3d sec5_2_large_sphere_20dx3d
table4_1_mass_holdup sec4_1_4_gamma table4_2_stiffness sec5_2_large_sphere_100dx1d table4_3_hunt"
exec "$(dirname "$0")/run_thesis_cases.sh" lan1994 "$ALL" "$@"
