# Included by the Makefile (make runs in the repository's root; the paths are from there).
.PHONY: bench bench-search bench-sweep bench-house bench-thrust bench-fuel

# ---- benchmarks: each stage's wall time (bench.sh), the search audit, the P01 bench grid -------
bench: $(TOOLS_STAMP) bench-sweep bench-search bench-house bench-thrust bench-fuel
	tests/bench/bench.sh

# The GTO -> GEO minimum-time family t_f(T_max) from 60 N down to 0.5 N, each cold (tests/bench/thrust_family.sh).
bench-thrust: $(TOOLS_STAMP)
	tests/bench/thrust_family.sh

# Minimum fuel at 1.5 t_min with and without the route from the minimum time, 60 to 10 N
# (tests/bench/fuel_from_time.sh).
bench-fuel: $(TOOLS_STAMP)
	tests/bench/fuel_from_time.sh

# The search audit: the default search against an exhaustive one, seeds 1-5 (tests/bench/search_audit.sh).
bench-search: $(TOOLS_STAMP)
	tests/bench/search_audit.sh

# The finer P01 grid (sweep.json's "bench"), with warm starts then every cell cold, each from an
# empty compile cache in a fresh runs folder, timed; tests/bench/sweep_summary.sh prints its figures.
bench-sweep: $(TOOLS_STAMP)
	@for start in warm cold; do runs=$$(mktemp -d); t0=$$(date +%s.%N); \
	  $(MAKE) --no-print-directory sweep sweep=P01 SWEEP_GRID=bench SWEEP_START=$$start RUNS_ROOT=$$runs >/dev/null; \
	  wall=$$(echo "$$(date +%s.%N) - $$t0" | bc); \
	  echo "bench-sweep: P01 bench grid, $$start starts, empty compile cache: $$wall s wall"; \
	  tests/bench/sweep_summary.sh $$runs/$(BACKEND)/P01-bench$$([[ $$start == cold ]] && echo -cold) $$wall; \
	  rm -rf $$runs; done

# The house's figures: raw JSON reads outside the reading rooms, the files spelling the names
# grammar, the ten longest functions (tests/bench/house.sh).
bench-house:
	tests/bench/house.sh
