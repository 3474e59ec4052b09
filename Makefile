# Thin wrapper: the two set-up commands of the README, plus bench.
# `make demo` and `make test` install missing Debian packages first (tools/install_deps.sh).
JOBS ?= $(shell nproc)
PYTHON := /usr/bin/python3
GRAINFLOW := build/release/grainflow

.PHONY: all deps release debug demo test test-debug bench fuzz clean python

all: release

deps:
	./tools/install_deps.sh

release: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

debug: deps
	cmake --preset debug
	cmake --build --preset debug -j $(JOBS)

# The demo builds the program only, not the tests and benchmarks.
demo: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS) --target grainflow
	$(GRAINFLOW) run cases/demo/vibrated_bed.toml -o runs/demo
	$(GRAINFLOW) plot runs/demo
	@echo "demo: figures in runs/demo/ (profiles.png, mass_below.png, timeseries.png, snapshots_phases.png)"

# Release build: every test. Debug build (AddressSanitizer + UBSan): the unit tests, built alone,
# except the long physics runs below (most of the sanitizer pass's time), which repeat for many
# steps code that shorter unit tests run under the sanitizers too; the release build runs them all.
SANITIZER_LONG_RUNS = NeighborList.EveryOverlappingPairIsListedAtEveryStep|GeometryWalls.SphereInATurningDrumSettlesWhereFrictionBalancesGravity|MeshWalls.ABedInAFacetedCylinderApproachesTheAnalyticCylinder|ElasticGas.EnergyErrorShrinksAsTimeStepSquared|EdmdCouetteServo.SymmetricServoGivesEqualTemperaturesAtTheTwoWalls|EdmdChute.TwentyDegreesRuns1e7EventsWithoutStalling|KineticTheorySolver.GlassBedsOfTable43|KineticTheorySolver.StrongerDriveExpandsTheBed|KineticTheorySolver.DenseBedStaysBelowClosePacking|EdmdEquationOfState.HardSpheresMatchCarnahanStarling|EdmdEnergyBudget.ClosesWithCampbellsReseparation
test: release
	cmake --preset debug
	cmake --build --preset debug -j $(JOBS) --target unit_tests
	ctest --preset release -j $(JOBS)
	ctest --preset debug -L unit -E '^($(SANITIZER_LONG_RUNS))$$' -j $(JOBS)

# The Python package, importable by /usr/bin/python3 from any folder afterwards: the release build
# (which builds the module) and a grainflow.pth in the user's site-packages naming its folder.
python: release
	@site=$$($(PYTHON) -m site --user-site) && mkdir -p "$$site" && \
	  echo "$(CURDIR)/build/release/python" > "$$site/grainflow.pth" && \
	  echo "python: import grainflow works for $(PYTHON) (via $$site/grainflow.pth)"

bench: release
	./bench/run_bench.sh

# libFuzzer over case files and particle files (clang, ASan + UBSan), FUZZ_SECONDS per target,
# seeded with the bundled cases; findings land in build/fuzz/findings/ (docs/ROBUSTNESS.md).
FUZZ_SECONDS ?= 60
fuzz:
	./tools/install_deps.sh fuzz
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)
	./tools/run_fuzz.sh $(FUZZ_SECONDS)

clean:
	rm -rf build
