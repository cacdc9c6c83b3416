# HELIOS: problem text -> spec -> derivation -> verify -> shoot.cpp -> solution -> score.
# make help lists the targets and variables; make scenario=S01 runs one scenario, make test the tests.
SHELL := bash
.SHELLFLAGS := -euo pipefail -c
.DELETE_ON_ERROR:
.SUFFIXES:
MAKEFLAGS += --warn-undefined-variables --no-builtin-rules

# The scenario and the sweep may be spelled scenario= / sweep= or SCENARIO= / SWEEP=; the Makefile
# uses the lower-case names, and refuses both spellings with different values.
define one_spelling
ifneq ($$(origin $(2)),undefined)
  ifneq ($$(origin $(1)),undefined)
    ifneq ($$($(1)),$$($(2)))
      $$(error $(1)=$$($(1)) and $(2)=$$($(2)) differ: give one of them)
    endif
  endif
  override $(1) := $$($(2))
endif
endef
$(eval $(call one_spelling,scenario,SCENARIO))
$(eval $(call one_spelling,sweep,SWEEP))
# problem=PATH: any folder holding a problem.txt (settings.json and reference.json optional), anywhere;
# it is scenario=<its name> of SCENARIOS_DIR=<the folder it is in>, its run in $(RUNS_ROOT)/<backend>/<its name>.
problem ?=
ifneq ($(value problem),)
  problem_path := $(patsubst %/,%,$(value problem))
  ifneq ($(origin scenario),undefined)
    $(error problem=$(value problem) and scenario=$(value scenario) both name the problem: give one of them)
  endif
  ifneq ($(origin SCENARIOS_DIR),undefined)
    $(error problem=$(value problem) and SCENARIOS_DIR=$(value SCENARIOS_DIR) both name the folder: give one of them)
  endif
  override scenario := $(notdir $(problem_path))
  override SCENARIOS_DIR := $(or $(patsubst %/,%,$(dir $(problem_path))),.)
endif
scenario ?= S01
# Where the scenarios are (tests point it at a private folder), each a folder of problem.txt and,
# optional, settings.json (the solver's defaults without it) and reference.json (scored without
# it: "no reference"); a sweep's: problem.txt, settings.json, sweep.json.
SCENARIOS_DIR ?= scenarios
BACKEND ?= builtin
# advisory: a failed verification is recorded and scored but does not stop the chain; strict: it stops.
VERIFY_MODE ?= advisory
# Prefix for the solve step, e.g. LAUNCH="srun -c2" on a cluster.
LAUNCH ?=
# The solve's wall-clock limit: a safety net (a search stops on its own rules, counted in work).
SOLVE_TIME_LIMIT ?= 3600
# llm backend: derive <-> verify rounds, and gen <-> compile rounds (1 generation + repairs).
DERIVE_ROUNDS ?= 3
GEN_ROUNDS ?= 4
# llm backend: a name for the run folder runs/llm-<RUN_TAG> (e.g. one per model), and the
# parser backend (llm by default; builtin to start from the deterministic spec).
RUN_TAG ?=
PARSE_BACKEND ?= $(BACKEND)
# Where runs go (tests point it at a private folder).
RUNS_ROOT ?= runs

# ---- names and folders are data --------------------------------------------------------------
# Recipes quote every path, and a name or folder that reaches them is refused unless it is plain:
# a name (scenario, sweep, RUN_TAG, SWEEP_GRID, a scenario's folder) of A-Z a-z 0-9 _ -, a folder
# variable of those and . / + (no blank, quote, $$ or other shell or make syntax), a count of
# digits. The variables are checked by their text before make expands it.
empty :=
space := $(empty) $(empty)
tab := $(empty)	$(empty)
define newline


endef
DIGITS := 0 1 2 3 4 5 6 7 8 9
NAME_CHARS := $(DIGITS) a b c d e f g h i j k l m n o p q r s t u v w x y z \
  A B C D E F G H I J K L M N O P Q R S T U V W X Y Z _ -
PATH_CHARS := $(NAME_CHARS) . / +
# without TEXT,CHARS: TEXT with each of CHARS removed, blanks first turned into '?' (so they stay).
without = $(if $(2),$(call without,$(subst $(firstword $(2)),,$(1)),$(wordlist 2,$(words $(2)),$(2))),$(1))
unplain = $(call without,$(subst $(space),?,$(subst $(tab),?,$(subst $(newline),?,$(1)))),$(2))
# check_text NAME,TEXT,CHARS,WHAT[,optional]: stops unless TEXT is made of CHARS (and not empty
# unless optional), naming the variable NAME; check_plain VARIABLE,... checks a variable's own text.
check_text = $(if $(or $(call unplain,$(2),$(3)),$(if $(5)$(2),,empty)),\
  $(error $(1)='$(2)' is not $(4): use only $(if $(filter .,$(3)),A-Z a-z 0-9 _ - . / +,$(if $(filter a,$(3)),A-Z a-z 0-9 _ -,digits))))
check_plain = $(call check_text,$(1),$(value $(1)),$(2),$(3),$(4))
$(call check_plain,problem,$(PATH_CHARS),a plain folder,optional)
$(call check_plain,SCENARIOS_DIR,$(PATH_CHARS),a plain folder)
$(call check_plain,RUNS_ROOT,$(PATH_CHARS),a plain folder)
$(call check_plain,scenario,$(NAME_CHARS),a scenario name)
$(call check_plain,RUN_TAG,$(NAME_CHARS),a plain name,optional)
$(foreach v,SOLVE_TIME_LIMIT DERIVE_ROUNDS GEN_ROUNDS,$(call check_plain,$(v),$(DIGITS),a count))
# A folder of SCENARIOS_DIR (but a hidden one) is a scenario's name; the first one that is not plain.
UNPLAIN_SCENARIO := $(if $(problem),,$(shell find -L '$(SCENARIOS_DIR)' -mindepth 1 -maxdepth 1 \( -type d -o -name 'S[0-9]*' \) \
  ! -name '.*' ! -regex '.*/[A-Za-z0-9_-]+' -printf '%P' -quit 2>/dev/null | LC_ALL=C tr -c '[:print:]' '?'))
ifneq ($(UNPLAIN_SCENARIO),)
  $(error $(SCENARIOS_DIR)/$(UNPLAIN_SCENARIO) is not a scenario name: rename the folder to A-Z a-z 0-9 _ - only)
endif

BUILD := build
BIN := $(BUILD)/bin
RUNS := $(RUNS_ROOT)/$(BACKEND)$(if $(RUN_TAG),-$(RUN_TAG))
CACHE := $(RUNS_ROOT)/.cache
$(foreach v,BUILD CACHE,$(call check_plain,$(v),$(PATH_CHARS),a plain folder))
SCENARIOS := $(notdir $(wildcard $(SCENARIOS_DIR)/S[0-9]*))
TOOLS := parse derive verify gen solve score
TOOL_BINS := $(addprefix $(BIN)/helios-,$(TOOLS))
TOOL_SOURCES := CMakeLists.txt $(shell find tools templates schemas prompts cmake -type f -not -name '*.sh')
TOOLS_STAMP := $(BUILD)/tools.stamp
# The llm backend reads its prompts at run time (they are not compiled into the tools): from the
# project's prompts/, each a prerequisite of the llm rules that send it, and of no builtin rule.
HELIOS_PROMPTS_DIR ?= $(CURDIR)/prompts
export HELIOS_PROMPTS_DIR
ifneq ($(filter llm,$(BACKEND) $(PARSE_BACKEND)),)
  $(call check_text,HELIOS_PROMPTS_DIR,$(HELIOS_PROMPTS_DIR),$(PATH_CHARS),a plain folder)
endif
LLM_PROMPT = $(if $(filter llm,$(2)),$(HELIOS_PROMPTS_DIR)/$(1))

ifeq ($(filter $(BACKEND),builtin llm),)
  $(error BACKEND=$(BACKEND) is not a backend of this build (use builtin or llm))
endif
ifeq ($(filter $(PARSE_BACKEND),builtin llm),)
  $(error PARSE_BACKEND=$(PARSE_BACKEND) is not a backend of this build (use builtin or llm))
endif
ifeq ($(filter $(VERIFY_MODE),advisory strict),)
  $(error VERIFY_MODE=$(VERIFY_MODE) is not advisory or strict)
endif
VERIFY_FLAGS := $(if $(filter advisory,$(VERIFY_MODE)),--advisory,)

# Every artifact is named here, so make treats none as intermediate: a deleted one is remade.
# The llm backend's refinement rounds are numbered artifacts on an explicit chain:
# derivation.r1 -> verify.r1 -> derivation.r2 -> ... and shoot.r1 -> compile.r1 -> shoot.r2 -> ...
# A round whose predecessor passed is written unchanged without asking the model, and
# derivation.json / shoot.cpp link to the last round.
derive_rounds := $(shell seq 1 $(DERIVE_ROUNDS))
gen_rounds := $(shell seq 1 $(GEN_ROUNDS))
ROUND_ARTIFACTS := $(foreach k,$(derive_rounds),derivation.r$(k).json $(if $(filter $(k),$(DERIVE_ROUNDS)),,verify.r$(k).json)) \
                   $(foreach k,$(gen_rounds),shoot.r$(k).cpp $(if $(filter $(k),$(GEN_ROUNDS)),,compile.r$(k).json))
ARTIFACTS := spec.json $(if $(filter llm,$(BACKEND)),$(ROUND_ARTIFACTS)) derivation.json verify.json shoot.cpp \
             solution.json trajectory.oem report.md score.json
artifacts_of = $(addprefix $(RUNS)/$(1)/,$(ARTIFACTS))

# helios-solve exits 5 when the artifact it wrote shows the problem infeasible: the run is
# complete (its score and report say so), and the chain goes on.
SOLVED := || test $$? -eq 5

.PHONY: run all scoreboard test unit bats tools deps clean sweep help catalogue
run: $(call artifacts_of,$(scenario))

all: $(foreach s,$(SCENARIOS),$(call artifacts_of,$(s)))

deps:
	@tools/install-deps.sh

$(BUILD)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B '$(BUILD)' -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=ON >/dev/null

# The tools are rebuilt when any library, tool, template or schema source changes.
$(TOOLS_STAMP): $(BUILD)/build.ninja $(TOOL_SOURCES)
	cmake --build '$(BUILD)' --target $(addprefix helios-,$(TOOLS)) helios-prompts helios-runtime
	touch '$@'

# Each artifact depends on the tool that writes it through that tool's content stamp, which
# changes only when the tool's bytes do: a rebuild that leaves a tool the same (a touched source,
# an edit of another tool) re-runs nothing it made. helios-gen (which names the runtime in
# shoot.cpp) and helios-solve (which links it) stamp the prebuilt runtime's bytes too.
RUNTIME_FILES := $(addprefix $(BUILD)/include/helios-runtime/,helios_runtime.hpp runtime_records.hpp runtime_calls.hpp \
  module_interface.hpp) $(BUILD)/lib/libhelios-runtime.a
$(BUILD)/stamps/helios-%: $(TOOLS_STAMP)
	@mkdir -p '$(@D)'
	@cat '$(BIN)/helios-$*' $(if $(filter gen solve,$*),$(foreach f,$(RUNTIME_FILES),'$(f)')) | sha256sum >'$@.new' && \
	  if cmp -s '$@.new' '$@'; then rm '$@.new'; else mv '$@.new' '$@'; fi
TOOL_STAMP = $(BUILD)/stamps/helios-$(1)
# Named here, so make does not take them for intermediate files and delete them.
TOOL_STAMPS := $(foreach t,$(TOOLS),$(call TOOL_STAMP,$(t)))

tools: $(TOOLS_STAMP) $(TOOL_STAMPS)

$(RUNS)/%/spec.json: $(SCENARIOS_DIR)/%/problem.txt $(call TOOL_STAMP,parse) $(call LLM_PROMPT,parse.txt,$(PARSE_BACKEND))
	@mkdir -p '$(@D)'
	'$(BIN)/helios-parse' --backend $(PARSE_BACKEND) '$<' -o '$@'

$(RUNS)/%/verify.json: $(RUNS)/%/derivation.json $(call TOOL_STAMP,verify)
	'$(BIN)/helios-verify' $(VERIFY_FLAGS) '$<' -o '$@'

ifeq ($(BACKEND),builtin)
$(RUNS)/%/derivation.json: $(RUNS)/%/spec.json $(call TOOL_STAMP,derive)
	'$(BIN)/helios-derive' '$<' -o '$@'

$(RUNS)/%/shoot.cpp: $(RUNS)/%/derivation.json $(RUNS)/%/verify.json $(call TOOL_STAMP,gen)
	'$(BIN)/helios-gen' '$<' -o '$@'
else
# Static pattern rules over the explicit list of every scenario's rounds: each round is its own
# rule (make would not reuse one implicit rule twice in a chain), every round file is a named
# target, so an interrupted run resumes at the first missing round.
LLM_SCENARIOS := $(sort $(SCENARIOS) $(scenario))
each_run = $(foreach s,$(LLM_SCENARIOS),$(RUNS)/$(s)/$(1))

$(call each_run,derivation.r1.json): $(RUNS)/%/derivation.r1.json: $(RUNS)/%/spec.json $(call TOOL_STAMP,derive) \
    $(HELIOS_PROMPTS_DIR)/pmp_derive.txt
	'$(BIN)/helios-derive' --backend llm --round 1 '$<' -o '$@'

# Verification of a round is advisory: its failed checks are the next round's feedback.
define derive_round
$(call each_run,verify.r$(2).json): $(RUNS)/%/verify.r$(2).json: $(RUNS)/%/derivation.r$(2).json $(call TOOL_STAMP,verify)
	'$(BIN)/helios-verify' --advisory '$$<' -o '$$@'

$(call each_run,derivation.r$(1).json): $(RUNS)/%/derivation.r$(1).json: $(RUNS)/%/spec.json \
    $(RUNS)/%/derivation.r$(2).json $(RUNS)/%/verify.r$(2).json $(call TOOL_STAMP,derive) $(HELIOS_PROMPTS_DIR)/pmp_derive.txt
	'$(BIN)/helios-derive' --backend llm --round $(1) --previous '$$(@D)/derivation.r$(2).json' \
	  --feedback '$$(@D)/verify.r$(2).json' '$$<' -o '$$@'
endef
$(foreach k,$(wordlist 2,$(DERIVE_ROUNDS),$(derive_rounds)),$(eval $(call derive_round,$(k),$(word $(k),0 $(derive_rounds)))))

# The final derivation is the last round (a relative link: make sees the round's time stamp).
$(call each_run,derivation.json): $(RUNS)/%/derivation.json: $(RUNS)/%/derivation.r$(DERIVE_ROUNDS).json
	ln -sfn '$(<F)' '$@'

$(call each_run,shoot.r1.cpp): $(RUNS)/%/shoot.r1.cpp: $(RUNS)/%/derivation.json $(RUNS)/%/verify.json $(call TOOL_STAMP,gen) \
    $(HELIOS_PROMPTS_DIR)/codegen.txt
	'$(BIN)/helios-gen' --backend llm --round 1 '$<' -o '$@'

define gen_round
$(call each_run,compile.r$(2).json): $(RUNS)/%/compile.r$(2).json: $(RUNS)/%/shoot.r$(2).cpp $(call TOOL_STAMP,solve)
	'$(BIN)/helios-solve' --backend llm --compile-only --cache-dir '$(CACHE)' '$$<' -o '$$@'

$(call each_run,shoot.r$(1).cpp): $(RUNS)/%/shoot.r$(1).cpp: $(RUNS)/%/derivation.json \
    $(RUNS)/%/shoot.r$(2).cpp $(RUNS)/%/compile.r$(2).json $(call TOOL_STAMP,gen) $(HELIOS_PROMPTS_DIR)/codegen.txt $(HELIOS_PROMPTS_DIR)/repair.txt
	'$(BIN)/helios-gen' --backend llm --round $(1) --previous '$$(@D)/shoot.r$(2).cpp' \
	  --compile-report '$$(@D)/compile.r$(2).json' '$$<' -o '$$@'
endef
$(foreach k,$(wordlist 2,$(GEN_ROUNDS),$(gen_rounds)),$(eval $(call gen_round,$(k),$(word $(k),0 $(gen_rounds)))))

$(call each_run,shoot.cpp): $(RUNS)/%/shoot.cpp: $(RUNS)/%/shoot.r$(GEN_ROUNDS).cpp
	ln -sfn '$(<F)' '$@'
endif

# trajectory.csv and the plots are written before solution.json, which marks the stage done.
# settings.json and reference.json are optional: a prerequisite where the folder has one
# (secondary expansion looks when the rule is used); without settings the solver's defaults, without
# a reference a score that says "no reference".
.SECONDEXPANSION:
optional_input = $(wildcard $(SCENARIOS_DIR)/$(1)/$(2))
$(RUNS)/%/solution.json: $(RUNS)/%/shoot.cpp $(RUNS)/%/spec.json $$(call optional_input,$$*,settings.json) \
                         $(call TOOL_STAMP,solve)
	$(LAUNCH) '$(BIN)/helios-solve' --backend $(BACKEND) '$<' \
	  $(if $(call optional_input,$*,settings.json),--settings '$(SCENARIOS_DIR)/$*/settings.json') --spec '$(@D)/spec.json' \
	  --cache-dir '$(CACHE)' --time-limit $(SOLVE_TIME_LIMIT) --trajectory '$(@D)/trajectory.csv' --plots '$(@D)/' \
	  -o '$@' $(SOLVED)

# The converged trajectory as a CCSDS OEM 2.0 (tools/lib/src/oem/README.md).
# trajectory.csv is written before solution.json and only for a converged solution, so it is no
# prerequisite: for a run that did not converge helios-score writes nothing (and removes a stale
# OEM) and exits 0, so make goes on; the target stays missing and this cheap step runs again at each
# make of that run.
$(RUNS)/%/trajectory.oem: $(RUNS)/%/spec.json $(RUNS)/%/solution.json $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' --oem --spec '$(@D)/spec.json' --solution '$(@D)/solution.json' \
	  --trajectory '$(@D)/trajectory.csv' -o '$@'

# The run as a document: the derivation as LaTeX mathematics beside verify's verdicts, the
# solution and its plots (tools/lib/src/report/README.md).
$(RUNS)/%/report.md: $(SCENARIOS_DIR)/%/problem.txt $(RUNS)/%/spec.json $(RUNS)/%/derivation.json $(RUNS)/%/verify.json \
                     $(RUNS)/%/solution.json $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' --report --problem '$<' --spec '$(@D)/spec.json' --derivation '$(@D)/derivation.json' \
	  --verify '$(@D)/verify.json' --solution '$(@D)/solution.json' -o '$@'

$(RUNS)/%/score.json: $(RUNS)/%/spec.json $(RUNS)/%/derivation.json $(RUNS)/%/verify.json $(RUNS)/%/solution.json \
                      $$(call optional_input,$$*,reference.json) $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' $(if $(call optional_input,$*,reference.json),--reference '$(SCENARIOS_DIR)/$*/reference.json',--no-reference '$*') \
	  --spec '$(@D)/spec.json' --derivation '$(@D)/derivation.json' --verify '$(@D)/verify.json' \
	  --solution '$(@D)/solution.json' -o '$@'

# ---- launch-window sweeps (tools/lib/src/sweep/README.md) ------------------------------------
# make sweep sweep=P01 [SWEEP_GRID=bench] [LAUNCH="srun -n1 -c1"] [-j N]: first each departure's
# feasibility boundary b<epoch>/ (the template's problem in minimum time; boundary.mk names them),
# then every cell d<epoch>_t<tof> of scenarios/P01/sweep.json not below its boundary, each a run
# folder under $(RUNS)/P01 (the bench grid: P01-bench) with the normal chain parse -> derive ->
# verify -> gen -> solve. The cells of one departure row are a chain along increasing tof: the
# first feasible one solved cold, each next one warm from the one before (its solution.json is a
# prerequisite), so make -j runs the rows in parallel. cells.mk (written by helios-score
# --sweep-cells once the boundaries are solved) names the cells and the chains. Then the
# neighbour cross-check (crosscheck.json) and sweep.csv with porkchop.png.
sweep ?=
SWEEP_GRID ?=
# cold: every cell searches cold (no --warm-start; its own folder <P>-cold), to measure the warm starts.
SWEEP_START ?= warm
ifeq ($(filter $(SWEEP_START),warm cold),)
  $(error SWEEP_START=$(SWEEP_START) is not warm or cold)
endif
# Cross-check solves at a time (make's -j does not reach into one recipe).
SWEEP_JOBS ?= 2
$(call check_plain,sweep,$(NAME_CHARS),a sweep name,optional)
$(call check_plain,SWEEP_GRID,$(NAME_CHARS),a grid name,optional)
$(call check_plain,SWEEP_JOBS,$(DIGITS),a count)
# A scenario is a folder of SCENARIOS_DIR with a problem.txt, a sweep one with a sweep.json (whatever
# their names); make scenario=X (the goal run, make's default) of any other X says so with the list,
# rather than make's "No rule to make target".
KNOWN_PROBLEMS := $(sort $(patsubst $(SCENARIOS_DIR)/%/problem.txt,%,$(wildcard $(SCENARIOS_DIR)/*/problem.txt)))
KNOWN_SWEEPS := $(sort $(patsubst $(SCENARIOS_DIR)/%/sweep.json,%,$(wildcard $(SCENARIOS_DIR)/*/sweep.json)))
KNOWN_SCENARIOS := $(filter-out $(KNOWN_SWEEPS),$(KNOWN_PROBLEMS))
ifneq ($(filter run,$(or $(MAKECMDGOALS),run)),)
  ifneq ($(problem),)
    ifeq ($(wildcard $(problem_path)/problem.txt),)
      $(error problem=$(value problem): $(problem_path)/problem.txt is missing$(if $(filter /%,$(problem_path)),, (a relative path starts at $(CURDIR))))
    endif
  endif
  ifneq ($(filter $(scenario),$(KNOWN_SWEEPS)),)
    $(error $(SCENARIOS_DIR)/$(scenario) is a sweep (it has a sweep.json): use make sweep sweep=$(scenario))
  endif
  ifeq ($(filter $(scenario),$(KNOWN_SCENARIOS)),)
    $(error scenario=$(scenario) is not a scenario of $(SCENARIOS_DIR)/: use one of $(KNOWN_SCENARIOS)$(if $(KNOWN_SWEEPS), (sweeps, make sweep sweep=..: $(KNOWN_SWEEPS))))
  endif
endif
ifneq ($(sweep),)
ifneq ($(BACKEND),builtin)
  $(error make sweep runs the builtin backend only (BACKEND=$(BACKEND)))
endif
ifeq ($(wildcard $(SCENARIOS_DIR)/$(sweep)/sweep.json),)
  $(error sweep=$(sweep) is not a sweep of $(SCENARIOS_DIR)/ (no sweep.json): use one of $(patsubst $(SCENARIOS_DIR)/%/sweep.json,%,$(wildcard $(SCENARIOS_DIR)/*/sweep.json)))
endif
SWEEP_DIR := $(RUNS)/$(sweep)$(if $(SWEEP_GRID),-$(SWEEP_GRID))$(if $(filter cold,$(SWEEP_START)),-cold)
SWEEP_SOURCES := $(SCENARIOS_DIR)/$(sweep)/sweep.json $(SCENARIOS_DIR)/$(sweep)/problem.txt
SWEEP_SETTINGS := $(SCENARIOS_DIR)/$(sweep)/settings.json
SWEEP_GRID_FLAG := $(if $(SWEEP_GRID),--grid $(SWEEP_GRID))
SWEEP_BOUNDARY :=
$(SWEEP_DIR)/boundary.mk: $(SWEEP_SOURCES) $(SWEEP_SETTINGS) $(call TOOL_STAMP,score) $(call TOOL_STAMP,parse)
	@mkdir -p '$(@D)'
	'$(BIN)/helios-score' --sweep-boundary '$<' --cells '$(@D)' --settings '$(SWEEP_SETTINGS)' $(SWEEP_GRID_FLAG) -o '$@'
-include $(SWEEP_DIR)/boundary.mk
SWEEP_BOUNDARY_SOLUTIONS := $(foreach b,$(SWEEP_BOUNDARY),$(SWEEP_DIR)/$(b)/solution.json)
SWEEP_CELLS :=
$(SWEEP_DIR)/cells.mk: $(SWEEP_SOURCES) $(SWEEP_DIR)/boundary.mk $(SWEEP_BOUNDARY_SOLUTIONS) $(call TOOL_STAMP,score)
	@mkdir -p '$(@D)'
	'$(BIN)/helios-score' --sweep-cells '$<' --cells '$(@D)' $(SWEEP_GRID_FLAG) -o '$@'
-include $(SWEEP_DIR)/cells.mk
SWEEP_SOLUTIONS := $(foreach c,$(SWEEP_CELLS),$(SWEEP_DIR)/$(c)/solution.json)
# A cell's and a boundary's artifacts are kept (make would delete them as intermediate, and redo them).
.SECONDARY: $(foreach c,$(SWEEP_CELLS) $(SWEEP_BOUNDARY),$(addprefix $(SWEEP_DIR)/$(c)/,problem.txt spec.json derivation.json verify.json shoot.cpp))

$(SWEEP_DIR)/%/spec.json: $(SWEEP_DIR)/%/problem.txt $(call TOOL_STAMP,parse)
	'$(BIN)/helios-parse' --backend builtin '$<' -o '$@'

# A boundary's solve: its own settings (the sweep's without the search budget), always cold.
$(SWEEP_BOUNDARY_SOLUTIONS): $(SWEEP_DIR)/%/solution.json: $(SWEEP_DIR)/%/shoot.cpp $(SWEEP_DIR)/boundary.mk \
                             $(call TOOL_STAMP,solve)
	$(LAUNCH) '$(BIN)/helios-solve' --backend builtin '$<' --settings '$(@D)/settings.json' --cache-dir '$(CACHE)' \
	  --time-limit $(SOLVE_TIME_LIMIT) --quiet --trajectory '$(@D)/trajectory.csv' -o '$@' $(SOLVED)

# A cell's solve, warm from its neighbour's solution.json when the chain gives it one.
$(SWEEP_SOLUTIONS): $(SWEEP_DIR)/%/solution.json: $(SWEEP_DIR)/%/shoot.cpp $(SWEEP_SETTINGS) $(call TOOL_STAMP,solve)
	$(LAUNCH) '$(BIN)/helios-solve' --backend builtin '$<' --settings '$(SWEEP_SETTINGS)' --cache-dir '$(CACHE)' \
	  --time-limit $(SOLVE_TIME_LIMIT) --quiet $(if $(and $(filter warm,$(SWEEP_START)),$(SWEEP_WARM_$*)),--warm-start '$(SWEEP_DIR)/$(SWEEP_WARM_$*)/solution.json') \
	  --trajectory '$(@D)/trajectory.csv' -o '$@' $(SOLVED)

# Every cell re-solved warm from its converged neighbours until none improves.
$(SWEEP_DIR)/crosscheck.json: $(SWEEP_DIR)/cells.mk $(SWEEP_SOLUTIONS) $(call TOOL_STAMP,score) $(call TOOL_STAMP,solve)
	'$(BIN)/helios-score' --sweep-crosscheck '$(SCENARIOS_DIR)/$(sweep)/sweep.json' --cells '$(@D)' --settings '$(SWEEP_SETTINGS)' \
	  --cache-dir '$(CACHE)' --solver '$(BIN)/helios-solve' --jobs $(SWEEP_JOBS) --time-limit $(SOLVE_TIME_LIMIT) \
	  $(if $(LAUNCH),--launch "$(LAUNCH)") $(SWEEP_GRID_FLAG) -o '$@'

# porkchop.png is drawn before sweep.csv, which marks the sweep done.
$(SWEEP_DIR)/sweep.csv: $(SWEEP_SOURCES) $(SWEEP_DIR)/cells.mk $(SWEEP_SOLUTIONS) $(SWEEP_DIR)/crosscheck.json \
                        $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' --sweep '$<' --cells '$(@D)' --crosscheck '$(@D)/crosscheck.json' $(SWEEP_GRID_FLAG) \
	  --porkchop '$(@D)/porkchop.png' -o '$@'
sweep: $(SWEEP_DIR)/sweep.csv
else
sweep:
	$(error make sweep needs sweep=<P scenario>, e.g. make sweep sweep=P01)
endif

# This backend's table, and the paper's three tables over every run folder under $(RUNS_ROOT).
scoreboard: $(RUNS)/scoreboard.md $(RUNS_ROOT)/scoreboard.md
$(RUNS)/scoreboard.md: $(wildcard $(RUNS)/S*/score.json) $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' --scoreboard '$(RUNS)' -o '$@'

$(RUNS_ROOT)/scoreboard.md: $(wildcard $(RUNS_ROOT)/*/*/score.json $(RUNS_ROOT)/*/*/*.transcript.json \
                              $(RUNS_ROOT)/*/*/compile.r*.json) $(call TOOL_STAMP,score)
	'$(BIN)/helios-score' --tables '$(RUNS_ROOT)' -o '$@'

unit: $(TOOLS_STAMP)
	cmake --build '$(BUILD)'
	ctest --test-dir '$(BUILD)' --output-on-failure -j2

# The tools' content stamps too: the pipeline tests run make with -o $(TOOLS_STAMP), under which
# a stamp left from before a source edit would be brought up to date only in the middle of a test.
bats: $(TOOLS_STAMP) $(TOOL_STAMPS)
	cmake --build '$(BUILD)' --target json-patch
	tests/run-bats.sh tests/bats

test: unit bats

# The schemas' parts the catalogue of terms makes (helios/pmp/catalogue.hpp), rewritten from it after
# a term is added or changed; the unit test catalogue_test holds them to it.
catalogue: $(TOOLS_STAMP)
	cmake --build '$(BUILD)' --target helios-test-catalogue
	HELIOS_WRITE_CATALOGUE=1 '$(BUILD)/helios-test-catalogue' --gtest_filter=Catalogue.TheSchemasAreWrittenFromIt

# ---- the rules of the test tree's tools, each in a fragment beside them -------------------------
# make test-sanitized: the suite under ASan and UBSan (build-asan).
include tests/sanitize/rules.mk
# make fuzz: the libFuzzer targets (build-fuzz).
include tests/fuzz/rules.mk
# make bench, bench-search, bench-sweep: the benchmarks.
include tests/bench/rules.mk

clean:
	rm -rf '$(BUILD)' $(ASAN_BUILD) $(FUZZ_BUILD) runs/builtin runs/llm runs/llm-* runs/scoreboard.md runs/.cache

# make help: the targets and variables a user sets (the rest of this file says how they work).
define HELP_TEXT
HELIOS: a low-thrust problem in words -> a solved, checked, scored trajectory (README.md).

Targets:
  make [scenario=S01]          one scenario's chain into runs/<backend>/<scenario>/ (the default goal)
  make problem=PATH            the same for any folder with a problem.txt (settings.json, reference.json optional)
  make all                     every scenario (-j works)
  make scoreboard              runs/<backend>/scoreboard.md, and the tables over every run in runs/scoreboard.md
  make sweep sweep=P01         a launch-window sweep (SWEEP_GRID=bench, SWEEP_START=cold)
  make test                    the unit tests (ctest) and the Bats suite
  make test-sanitized          the unit tests and the hostile-input Bats files under ASan/UBSan (build-asan)
  make fuzz                    each libFuzzer target for FUZZ_SECONDS (build-fuzz)
  make bench                   stage timings, the search audit (bench-search) and the P01 bench grid (bench-sweep)
  make tools | deps | clean    build the tools | install missing Debian packages | remove build trees and runs
  make catalogue               rewrite the schemas' parts the catalogue of terms makes (after adding a term)
  make help                    this text

Variables (scenario and sweep may also be spelled SCENARIO and SWEEP):
  scenario=S01                 one of: $(KNOWN_SCENARIOS); or problem=PATH, any folder with a problem.txt
  BACKEND=builtin|llm          who parses, derives and writes the program ($(BACKEND))
  VERIFY_MODE=advisory|strict  strict: a failed verification stops the chain ($(VERIFY_MODE))
  LAUNCH=                      a prefix of the solve step, e.g. LAUNCH="srun -n1 -c1"
  SOLVE_TIME_LIMIT=3600        seconds of one solve (a safety net)
  RUNS_ROOT=runs               where run folders go; SCENARIOS_DIR=scenarios where scenarios are read
  DERIVE_ROUNDS=3 GEN_ROUNDS=4 RUN_TAG= PARSE_BACKEND=   the llm backend's rounds, run folder tag, parser
  FUZZ_SECONDS=60              make fuzz: seconds of each target
endef
export HELP_TEXT
help:
	@echo "$$HELP_TEXT"
