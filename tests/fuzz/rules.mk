# Included by the Makefile (make runs in the repository's root; the paths are from there).
.PHONY: fuzz deps-fuzz

# ---- libFuzzer targets (tests/fuzz), built by clang++ in their own tree ------------------------
# Each target runs FUZZ_SECONDS from its seed corpus (tests/fuzz/corpus/<target>, and for the
# parser every scenario's problem.txt), a crash, a leak, a sanitizer error, an input running over
# 10 s or 2 GB is a finding written to build-fuzz/findings/<target>/; make fuzz fails on any.
FUZZ_BUILD := build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := parse json_spec json_derivation json_settings
FUZZ_MAX_LEN_parse := 8192
FUZZ_MAX_LEN_json_spec := 16384
FUZZ_MAX_LEN_json_derivation := 32768
FUZZ_MAX_LEN_json_settings := 2048
FUZZ_DICT_parse := tests/fuzz/parse.dict
FUZZ_DICT_json_spec := tests/fuzz/json.dict
FUZZ_DICT_json_derivation := tests/fuzz/json.dict
FUZZ_DICT_json_settings := tests/fuzz/json.dict
FUZZ_SEEDS_parse := $(wildcard scenarios/*/problem.txt) $(wildcard tests/fuzz/corpus/parse)
FUZZ_SEEDS_json_spec := $(wildcard tests/fuzz/corpus/json_spec)
FUZZ_SEEDS_json_derivation := $(wildcard tests/fuzz/corpus/json_derivation)
FUZZ_SEEDS_json_settings := $(wildcard scenarios/*/settings.json) $(wildcard tests/fuzz/corpus/json_settings)
FUZZ_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

deps-fuzz:
	@tools/install-deps.sh --fuzz

$(FUZZ_BUILD)/build.ninja: CMakeLists.txt | deps-fuzz
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DBUILD_TESTING=OFF -DHELIOS_FUZZ=ON >/dev/null

# Every target runs even when one has findings; make fuzz then fails.
fuzz: $(FUZZ_BUILD)/build.ninja
	cmake --build $(FUZZ_BUILD) --target fuzzers
	@status=0; \
	$(foreach t,$(FUZZ_TARGETS),$(FUZZ_ENV) tests/fuzz/run.sh $(FUZZ_BUILD) $(t) $(FUZZ_SECONDS) $(FUZZ_MAX_LEN_$(t)) \
	  $(FUZZ_DICT_$(t)) $(FUZZ_SEEDS_$(t)) || status=1;) exit $$status
