# Thin wrapper around CMake presets. The README's two commands:
#   make demo   installs what is missing, builds the Release CLI, runs the demo case
#   make test   installs what is missing, builds all of Release, runs the tests (CTest)
JOBS ?= $(shell nproc)

.PHONY: deps configure build build-cli demo test test-sanitize bench bench-cases bench-bodies bench-3d clean

deps:
	scripts/install-deps

configure: deps
	cmake --preset release

# Everything: the CLI, the Python module, the test programs and the benchmarks.
build: configure
	cmake --build --preset release -j $(JOBS)

# The CLI alone (its libraries), all that the demo runs: its plots are drawn by tools/plot_run.py,
# which reads the run with python/particula/reader.py from the source tree, no build needed.
build-cli: configure
	cmake --build --preset release -j $(JOBS) --target particula

# Paper case 7.2 (a cylinder settling in a closed box) at the coarsest level the body-size check
# allows (10 particles across the cylinder), up to 0.5 s, when it has reached its terminal speed.
demo: build-cli
	./build/release/particula run cases/falling_cylinder.toml --out runs/demo --overwrite \
	    --set resolution.d0=2.5e-4 --set time.end=0.5
	@echo "demo: see runs/demo/plots/bodies.png (settling velocity against Glowinski et al. 2001) and runs/demo/summary.json"

test: build
	ctest --preset release -j $(JOBS)

test-sanitize: deps
	cmake --preset sanitize
	cmake --build --preset sanitize -j $(JOBS)
	ctest --preset sanitize -j $(JOBS)

# End-to-end throughput of the falling cylinder at d0 = 1e-4 m (about 1.2e5 particles) on all
# cores, then the micro-benchmarks of each pass. BENCH_ARGS adds options, e.g. --d0 3.3e-5.
bench: build
	./build/release/bench/particula_bench_e2e --d0 1e-4 --steps 30 $(BENCH_ARGS)
	./build/release/bench/particula_bench --benchmark_min_time=0.5

# Time to solution of the five paper cases at the paper's resolution (the case files as shipped):
# each runs BENCH_STEPS steps after 20 warm-up steps and the benchmark extrapolates to the case's
# end time at the measured wall time per step. A few minutes in all on 2 cores.
# BENCH_ARGS adds options, e.g. --backend cuda or --threads 1.
BENCH_STEPS ?= 300
PAPER_CASES = shear_migration falling_cylinder two_cylinders_shear dkt ellipse_obstacle
bench-cases: build
	@for c in $(PAPER_CASES); do \
	  ./build/release/bench/particula_bench_e2e --case cases/$$c.toml --steps $(BENCH_STEPS) --warmup 20 $(BENCH_ARGS) \
	    | grep -E '^(case|particles|throughput|to the end|RESULT)' || exit 1; \
	done

# Cost of bodies: a step with 1000 free circles (10 particles across) in a closed box against a
# step of the same box with fluid only and the same particle count (bench/many_bodies.py writes
# both cases into build/bench-bodies). Both run untimed to t = BENCH_ADVANCE first (the bodies
# then fall at about their fastest), so that the timed steps build the kept band of the momentum
# loads as often as a developed flow does (BENCH_ADVANCE=0 times steps from rest).
# bench/bodies_cost.py times them in BENCH_ROUNDS alternating rounds and compares the mean
# seconds per step: one pair of runs varies as much as the cost measured. BENCH_ARGS go to
# particula_bench_e2e (e.g. BENCH_ARGS="--threads 1").
BENCH_ADVANCE ?= 0.04
BENCH_ROUNDS ?= 3
bench-bodies: build
	python3 bench/bodies_cost.py --bodies 1000 --rounds $(BENCH_ROUNDS) --steps 30 --advance $(BENCH_ADVANCE) $(BENCH_ARGS)

# 3D with the fluid solver (no case file yet): start-up flow in a square duct at 10, 20 and 40
# particles across against the series solution, with the 2D channel's cost per pair alongside
# (--plates), then Stokes flow through a simple cubic array of spheres against Zick & Homsy at
# 8, 12 and 16 particles across a sphere. About 25 minutes on 2 cores. BENCH3_ARGS adds options,
# e.g. --threads 1.
bench-3d: build
	./build/release/bench/particula_bench_duct3 --across 10 --across 20 --across 40 --plates $(BENCH3_ARGS)
	./build/release/bench/particula_bench_sphere_array3 --c 0.064 --across 8 --across 12 --across 16 $(BENCH3_ARGS)

clean:
	rm -rf build
