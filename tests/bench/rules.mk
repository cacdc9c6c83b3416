# Included by the Makefile (make runs in the repository's root; the paths are from there).
.PHONY: bench bench-search bench-sweep

# ---- benchmarks: each stage's wall time (bench.sh), the search audit, the P01 bench grid -------
bench: $(TOOLS_STAMP) bench-sweep bench-search
	tests/bench/bench.sh

# The search audit: the default search against an exhaustive one, seeds 1-5 (tests/bench/search_audit.sh).
bench-search: $(TOOLS_STAMP)
	tests/bench/search_audit.sh

# The finer P01 grid (sweep.json's "bench"), with warm starts then every cell cold, each timed
# (into RUNS_ROOT's P01-bench and P01-bench-cold: a finished grid is not redone).
bench-sweep: $(TOOLS_STAMP)
	@for start in warm cold; do t0=$$(date +%s.%N); \
	  $(MAKE) --no-print-directory sweep sweep=P01 SWEEP_GRID=bench SWEEP_START=$$start >/dev/null; \
	  echo "bench-sweep: P01 bench grid, $$start starts: $$(echo "$$(date +%s.%N) - $$t0" | bc) s wall"; \
	  tail -n +2 $(RUNS)/P01-bench$$([[ $$start == cold ]] && echo -cold)/sweep.csv | cut -d, -f4,7 | sort | uniq -c; done
