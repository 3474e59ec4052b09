#!/bin/bash
# Runs every study of Campbell 1982 Chapter 3 (cases/campbell1982) at full length into
# runs/campbell1982/, then analyze and plot (tools/run_thesis_cases.sh);
# docs/validation/campbell1982.md compares the results with the thesis. About 5 minutes on 2 cores.
# Usage: tools/run_campbell1982.sh [STUDY...]   (default: all; e.g. `tools/run_campbell1982.sh couette_rough`)
# Environment: GRAINFLOW (default build/release/grainflow), GRAINFLOW_JOBS (parallel sweep runs, default 2).
ALL="couette_noslip couette_shear_rate couette_noslip_normal_force couette_noslip_density couette_low_density_S
couette_rough couette_3d_spheres chute_40deg_5x4 chute_40deg_4x4 chute_40deg chute_30deg chute_30deg_wide
chute_20deg chute_depth_30deg chute_restitution_30deg chute_3d_spheres"
exec "$(dirname "$0")/run_thesis_cases.sh" campbell1982 "$ALL" "$@"
