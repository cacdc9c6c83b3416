# Included by the Makefile (make runs in the repository's root; the paths are from there).
.PHONY: test-sanitized

# ---- the suite under ASan and UBSan, in its own build tree ------------------------------------
# Every sanitizer error is fatal and exits 134 (abort), a code no test expects; a leak at exit too,
# except CLN's one allocation that lives until exit (tests/sanitize/lsan.supp). Each sanitized
# process writes its report to $(SANITIZE_LOGS)/report.<pid>, not into the output the tests compare;
# check-logs.sh then accepts only the table of that one suppressed 26-byte leak. A program
# helios-solve compiles at run time is built unsanitized by the system g++ and runs in the sandbox
# with an empty environment.
ASAN_BUILD := build-asan
SANITIZE_LOGS := $(CURDIR)/$(ASAN_BUILD)/sanitizer-logs
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_string_checks=1:log_path=$(SANITIZE_LOGS)/report \
  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The Bats files run under the sanitizers (the whole suite is too slow for CI's budget there): the
# readers of hostile input, and hostile.bats when the tree has it.
SANITIZED_BATS := $(wildcard $(addprefix tests/bats/,parse.bats derive.bats verify.bats gen.bats hostile.bats))

$(ASAN_BUILD)/build.ninja: CMakeLists.txt | deps
	cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_TESTING=ON -DHELIOS_SANITIZE=ON >/dev/null

# The build runs under the same options: it runs the test executables to list their tests.
test-sanitized: $(ASAN_BUILD)/build.ninja
	rm -rf $(SANITIZE_LOGS) && mkdir -p $(SANITIZE_LOGS)
	$(SANITIZE_ENV) cmake --build $(ASAN_BUILD)
	status=0; \
	$(SANITIZE_ENV) ctest --test-dir $(ASAN_BUILD) --output-on-failure -j2 || status=1; \
	$(SANITIZE_ENV) HELIOS_BUILD_DIR=$(ASAN_BUILD) BATS_JOBS=1 tests/run-bats.sh $(SANITIZED_BATS) || status=1; \
	tests/sanitize/check-logs.sh $(SANITIZE_LOGS) || status=1; \
	exit $$status
