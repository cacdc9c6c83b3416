# HELIOS: problem text -> spec -> derivation -> verify -> shoot.cpp -> solution -> score.
#   make scenario=S01 [BACKEND=builtin]   one scenario (default S01)
#   make all                               every scenario (-j works)
#   make scoreboard | test | bench | clean
SHELL := bash
.SHELLFLAGS := -euo pipefail -c
.DELETE_ON_ERROR:
.SUFFIXES:
MAKEFLAGS += --warn-undefined-variables --no-builtin-rules

scenario ?= S01
BACKEND ?= builtin
# advisory: a failed verification is recorded and scored but does not stop the chain; strict: it stops.
VERIFY_MODE ?= advisory
# Prefix for the solve step, e.g. LAUNCH="srun -c2" on a cluster.
LAUNCH ?=
SOLVE_TIME_LIMIT ?= 900

BUILD := build
BIN := $(BUILD)/bin
RUNS := runs/$(BACKEND)
CACHE := runs/.cache
SCENARIOS := $(notdir $(wildcard scenarios/S[0-9]*))
TOOLS := parse derive verify gen solve score
TOOL_BINS := $(addprefix $(BIN)/helios-,$(TOOLS))
TOOL_SOURCES := CMakeLists.txt $(shell find tools templates schemas cmake -type f -not -name '*.sh')
TOOLS_STAMP := $(BUILD)/tools.stamp

ifeq ($(BACKEND),builtin)
else
  $(error BACKEND=$(BACKEND): only the builtin backend is available in this build)
endif
VERIFY_FLAGS := $(if $(filter advisory,$(VERIFY_MODE)),--advisory,)

# Every artifact is named here, so make treats none as intermediate: a deleted one is remade.
ARTIFACTS := spec.json derivation.json verify.json shoot.cpp solution.json score.json
artifacts_of = $(addprefix $(RUNS)/$(1)/,$(ARTIFACTS))

.PHONY: run all scoreboard test unit bats bench tools deps clean
run: $(call artifacts_of,$(scenario))

all: $(foreach s,$(SCENARIOS),$(call artifacts_of,$(s)))

deps:
	@tools/install-deps.sh

$(BUILD)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON >/dev/null

# The tools are rebuilt when any library, tool, template or schema source changes.
$(TOOLS_STAMP): $(BUILD)/build.ninja $(TOOL_SOURCES)
	cmake --build $(BUILD) --target $(addprefix helios-,$(TOOLS))
	touch $@

tools: $(TOOLS_STAMP)

$(RUNS)/%/spec.json: scenarios/%/problem.txt $(TOOLS_STAMP)
	@mkdir -p $(@D)
	$(BIN)/helios-parse $< -o $@

$(RUNS)/%/derivation.json: $(RUNS)/%/spec.json $(TOOLS_STAMP)
	$(BIN)/helios-derive $< -o $@

$(RUNS)/%/verify.json: $(RUNS)/%/derivation.json $(TOOLS_STAMP)
	$(BIN)/helios-verify $(VERIFY_FLAGS) $< -o $@

$(RUNS)/%/shoot.cpp: $(RUNS)/%/derivation.json $(RUNS)/%/verify.json $(TOOLS_STAMP)
	$(BIN)/helios-gen $< -o $@

# trajectory.csv and the plots are written before solution.json, which marks the stage done.
$(RUNS)/%/solution.json: $(RUNS)/%/shoot.cpp scenarios/%/settings.json $(TOOLS_STAMP)
	$(LAUNCH) $(BIN)/helios-solve $< --settings scenarios/$*/settings.json --cache-dir $(CACHE) \
	  --time-limit $(SOLVE_TIME_LIMIT) --trajectory $(@D)/trajectory.csv --plots $(@D)/ -o $@

$(RUNS)/%/score.json: scenarios/%/reference.json $(RUNS)/%/spec.json $(RUNS)/%/derivation.json \
                      $(RUNS)/%/verify.json $(RUNS)/%/solution.json $(TOOLS_STAMP)
	$(BIN)/helios-score --reference $< --spec $(@D)/spec.json --derivation $(@D)/derivation.json \
	  --verify $(@D)/verify.json --solution $(@D)/solution.json -o $@

scoreboard: $(RUNS)/scoreboard.md
$(RUNS)/scoreboard.md: $(wildcard $(RUNS)/S*/score.json) $(TOOLS_STAMP)
	$(BIN)/helios-score --scoreboard $(RUNS) -o $@

unit: $(TOOLS_STAMP)
	cmake --build $(BUILD)
	ctest --test-dir $(BUILD) --output-on-failure -j2

bats: $(TOOLS_STAMP)
	tests/run-bats.sh tests/bats

test: unit bats

bench: $(TOOLS_STAMP)
	tests/bench/bench.sh

clean:
	rm -rf $(BUILD) runs/builtin runs/llm $(CACHE)
