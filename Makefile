# boltrom: build, run and test. `make` builds bin/boltrom; `make run` runs the main job;
# `make test` runs the test suite. Missing Debian packages are installed first
# (scripts/install-deps, needs root).
PETSC_DIR ?= /usr/lib/petsc
SLEPC_DIR ?= /usr/lib/slepc
export PETSC_DIR SLEPC_DIR

PYTHON   ?= /usr/bin/python3
NP       ?= 2
LEVEL    ?= 1
LEVELS   ?= 1
export OMPI_ALLOW_RUN_AS_ROOT = 1
export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM = 1
export OPENBLAS_NUM_THREADS = 1

SLEPC_VARS := $(wildcard $(SLEPC_DIR)/lib/slepc/conf/slepc_variables)
ifeq ($(SLEPC_VARS),)
# Nothing installed yet: install the stack, then run the same goal again.
.DEFAULT_GOAL := all
all bin/boltrom run test bench mesh tests-c verify stress stress-strict paper options:
	bash scripts/install-deps
	$(MAKE) $@
else
include $(SLEPC_VARS)

# sources by concern, one folder each (src/sys, model, contact, solve, rom, app): found recursively
LIB_SRC  := $(filter-out src/app/main.c,$(shell find src -name '*.c' | sort))
LIB_OBJ  := $(patsubst src/%.c,build/%.o,$(LIB_SRC))
TEST_SRC := $(wildcard tests/c/*.c)
TEST_BIN := $(patsubst tests/c/%.c,bin/%,$(TEST_SRC))
HEADERS  := $(shell find include -name '*.h')

WARN     := -Wall -Wextra -Wno-unused-parameter -Werror=implicit-function-declaration -Werror=implicit-int -Werror=return-type
CFLAGS_B := -O2 -g $(WARN) -Iinclude $(SLEPC_CC_INCLUDES)
LDLIBS_B := $(SLEPC_LIB) $(PETSC_LIB) -lmetis -lptscotch -lscotch -lm

.DEFAULT_GOAL := all
all: bin/boltrom $(TEST_BIN)

# the reduced model's per-element loops: vectorised (the cheap default declines loops of
# unknown length); vectorising independent lanes does not change a result's bits, nor does a
# wider vector while no multiply and add are contracted into one FMA
build/sys/exact_sum.o $(patsubst src/%.c,build/%.o,$(wildcard src/rom/rom*.c)): CFLAGS_B += -fvect-cost-model=dynamic -ffp-contract=off

build/%.o: src/%.c $(HEADERS)
	@mkdir -p $(dir $@)
	@echo "  CC  $<"
	@$(PCC) $(CFLAGS_B) -c $< -o $@

build/libboltrom.a: $(LIB_OBJ)
	@rm -f $@ && ar rcs $@ $^

bin/boltrom: src/app/main.c build/libboltrom.a $(HEADERS)
	@mkdir -p bin
	@echo "  LD  $@"
	@$(PCC) $(CFLAGS_B) $< build/libboltrom.a -o $@ $(LDLIBS_B)

bin/%: tests/c/%.c build/libboltrom.a $(HEADERS)
	@mkdir -p bin
	@echo "  LD  $@"
	@$(PCC) $(CFLAGS_B) $< build/libboltrom.a -o $@ $(LDLIBS_B)

tests-c: $(TEST_BIN)

deps:
	bash scripts/install-deps

MESH_LEVEL1 := output/mesh/joint-L$(LEVEL).msh
$(MESH_LEVEL1):
	@mkdir -p output/mesh
	$(PYTHON) scripts/mesh-joint --level $(LEVEL) --output $@

mesh: deps $(MESH_LEVEL1)

# The main job: the paper-level joint, tied (static, eigenfrequencies), then the paper's step
# scene on the full-order model with contact, plotted. (The reduced model: README.)
run: deps all $(MESH_LEVEL1)
	mpiexec -n $(NP) bin/boltrom -options_file inputs/tied-joint.yaml -mesh $(MESH_LEVEL1) \
	  -output_dir output/tied-joint -summary output/tied-joint/summary.json
	$(PYTHON) python/plot_static.py output/tied-joint/joint.h5 output/tied-joint/static.png
	mpiexec -n $(NP) bin/boltrom -options_file inputs/paper-step.yaml -mesh $(MESH_LEVEL1) \
	  -summary output/paper-step/summary.json
	$(PYTHON) python/plot_history.py output/paper-step/step.png output/paper-step/paper-step.h5

# Every FOM setting and the ROMs against a tight reference, each timed as the median of
# BENCH_REPEATS runs, with each ROM's offline and training times and the runs after which it pays
# off, on paper-step and on the scenes that open part of the joint (BENCH_SCENES) or are
# frictional (BENCH_FRICTION_SCENES); then the frictional sweep end to end (dissipation per cycle
# at 8 amplitudes, FOM against one ROM build and 8 ROM runs); FOM against ROM per mesh level.
BENCH_SCENES ?= P5k-F100 P10k-F300 P2k-C300x P5k-F300y
# frictional scenes (python/scenes.py), at the bench's level
BENCH_FRICTION_SCENES ?= mu0.1-P5k-S100x
BENCH_REPEATS ?= 5
bench: deps all
	$(PYTHON) scripts/bench-contact --np $(NP) --level $(LEVEL) --repeats $(BENCH_REPEATS)
	for s in $(BENCH_SCENES) $(BENCH_FRICTION_SCENES); do $(PYTHON) scripts/bench-contact --np $(NP) --level $(LEVEL) --repeats $(BENCH_REPEATS) --scene $$s || exit 1; done
	$(PYTHON) scripts/bench-sweep --np $(NP) --level $(LEVEL) --results
	$(PYTHON) scripts/bench-rom --np $(NP) --levels $(LEVELS)

# The paper's figures 3-6, table 3 and the eigenfrequency table under the paper's contact law
# (output/paper/) and re-measured under the strict law, the default (output/paper-strict/).
paper: deps all
	$(PYTHON) scripts/reproduce-paper --np $(NP)
	$(PYTHON) scripts/reproduce-paper --np $(NP) --law strict

# FOM and ROM stress sweep and the envelope table (output/stress/); the FOM's loop options.
stress: deps all
	$(PYTHON) scripts/stress --np $(NP)
	$(PYTHON) scripts/stress-fom --np $(NP)

# The strict contact law's FOM over the stress envelope (level 0.5) and the paper-step scene over
# mesh levels 0.5 and 1, one rank and one run at a time (output/stress-strict/, docs/results.md).
stress-strict: deps all
	$(PYTHON) scripts/stress-strict --results

# The joint under Coulomb friction: dissipation per cycle against the load amplitude, hysteresis
# loops and ring-down backbones at level 0.5 (output/friction-L0.5/, docs/results.md); then the
# harmonic loads along x and z with the ROM beside the FOM (output/friction-L0.5-rom/, -z-rom/);
# then eight cycles along x, each cycle's dissipation, with the slip-shape ROM and with the
# snapshot-mode ROM trained at 300 N and on a stepped sine from 10 to 300 N
# (output/friction-L0.5-rom-c8/, -rom-trained300-c8/, -rom-trained10to300-c8/); and three cycles
# up to 700 N, below the joint's sliding as a whole, with one trained on a stepped sine from 10 to
# 700 N (-rom-trained10to700/); then both again with cone shapes and 150 modes (-m150-cone), the
# harmonic loads along z with them, along x with the normal shapes alone (-m150-cone-normal-c8),
# and at level 1 on 2 ranks (about 26 min of the target's time). Last, the default ROM against the
# reduced contact's frictional acceptance over eight scenes at levels 0.5 and 1 (scripts/rom-friction,
# output/rom-friction-L*/, about 17 min), and the trained ROM over the same scenes, each trained on
# a stepped sine of its own (--trained, output/rom-friction-L*-trained/, about 35 min).
friction: deps all
	$(PYTHON) scripts/friction-scenes --results
	$(PYTHON) scripts/friction-scenes --rom --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --ringdown --direction z --results
	$(PYTHON) scripts/friction-scenes --rom --cycles 8 --amplitudes 10 30 100 300 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 300 --cycles 8 --amplitudes 10 30 100 300 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 300 --rom-train-from 10 --cycles 8 --amplitudes 10 20 30 50 100 200 300 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 700 --rom-train-from 10 --cycles 3 --amplitudes 50 200 500 700 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 300 --rom-train-from 10 --rom-cone 0.999 --rom-modes 150 --cycles 8 --amplitudes 10 20 30 50 100 200 300 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 700 --rom-train-from 10 --rom-cone 0.999 --rom-modes 150 --cycles 3 --amplitudes 50 200 500 700 --ringdown --results
	$(PYTHON) scripts/friction-scenes --rom --rom-train 300 --rom-train-from 10 --rom-cone 0.999 --rom-cone-normal --rom-modes 150 --cycles 8 --amplitudes 10 20 30 50 100 200 300 --ringdown --results
	$(PYTHON) scripts/friction-scenes --direction z --rom --rom-train 1000 --rom-train-from 10 --rom-cone 0.999 --rom-modes 150 --cycles 3 --amplitudes 10 30 100 300 1000 --ringdown --results
	$(PYTHON) scripts/friction-scenes --level 1 --np 2 --rom --rom-train 300 --rom-train-from 10 --rom-cone 0.999 --rom-modes 150 --cycles 8 --amplitudes 30 100 --ringdown --results
	$(PYTHON) scripts/rom-friction --level 0.5 --results
	$(PYTHON) scripts/rom-friction --level 1 --results
	$(PYTHON) scripts/rom-friction --level 0.5 --trained --results
	$(PYTHON) scripts/rom-friction --level 1 --trained --results

# The Brake-Reuss beam: its modes about the preloaded state (stuck, and the lap frictionless) at
# levels 0.5, 1 and 1.5, and its backbone from ring-downs with friction at levels 0.5 and 1 by
# the FOM and by one ROM, end to end, and at level 0.5 by the ROM trained on the largest
# ring-down's snapshots (output/brb-*, docs/results.md; about 55 min).
brb: deps all
	$(PYTHON) scripts/brb-modes --np $(NP) --levels 0.5 1 1.5 --results
	$(PYTHON) scripts/brb-backbone --np $(NP) --level 0.5 --rom --results
	$(PYTHON) scripts/brb-backbone --np $(NP) --level 1 --rom --results
	$(PYTHON) scripts/brb-backbone --np $(NP) --level 0.5 --rom --rom-snapshots --results

# The axial load with friction against CalculiX at level 1, the load point held (16 increments)
# and free (8), their JSON in docs/data/ and docs/ccx-friction-L1.png (docs/verification.md
# section 9; about 35 min, most of it ccx's).
ccx-friction: deps all
	$(PYTHON) scripts/ccx-crosscheck --level 1 --only friction --ranks $(NP) --friction-support --friction-steps 16 --workdir output/ccx-L1-held --json docs/data/ccx-friction-L1-held.json
	$(PYTHON) scripts/ccx-crosscheck --level 1 --only friction --ranks $(NP) --workdir output/ccx-L1-free --json docs/data/ccx-friction-L1-free.json
	$(PYTHON) python/plot_ccx_friction.py docs/ccx-friction-L1.png docs/data/ccx-friction-L1-held.json docs/data/ccx-friction-L1-free.json

# Verification figures quoted in the README (cantilever, joint over levels, partitioners).
verify: deps all
	$(PYTHON) scripts/verify-model --levels 1 2 3 --np $(NP)

test: deps all
	$(PYTHON) -m pytest -q --durations=15 tests

# docs/options.md: every option with its default and help, from bin/boltrom -help.
options: deps all
	$(PYTHON) scripts/options-doc

clean:
	rm -rf build bin

.PHONY: all deps run test mesh clean tests-c verify bench stress stress-strict paper options friction ccx-friction brb
endif
