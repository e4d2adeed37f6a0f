# Thin wrapper over CMake: `make demo` and `make test` work on a fresh Debian 12 machine.
BUILD ?= build
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?=
PREFIX ?= /usr/local

.PHONY: all deps configure build demo test test-quick bench accuracy install clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=$(PREFIX) $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

demo: build
	./$(BUILD)/fracterra demo out/
	@echo "demo: open out/index.html"

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The same suite without the statistical accuracy programs (CTest label "accuracy"): a quick run while editing.
test-quick: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE accuracy

bench: build
	./$(BUILD)/fracterra_bench
	/usr/bin/python3 bench/python/overhead.py $(BUILD)

# Arakawa & Krotkov Table 1 on the scattered-point estimator, every column (no noise, 30, 25, 20 dB on x, y, z)
# on the independent Stein generator, then z-only noise, then fracterra's own synthesizers;
# ACCURACY_FLAGS="--surfaces 20" for a shorter run (about 25 min on 2 loaded cores).
ACCURACY_FLAGS ?= --surfaces 100
# Arakawa & Krotkov Table 4 and the held-out RMSE against GRASS v.surf.rst (reconstruction).
ACCURACY_RECON_FLAGS ?= --surfaces 4
# Bias and RMSE of dim profile's madogram and variogram on exact fBm, n = 1024 and 4096, H = 0.25, 0.5, 0.75.
ACCURACY_PROFILE_FLAGS ?= --profiles 1000
accuracy: build
	./$(BUILD)/fracterra_accuracy $(ACCURACY_FLAGS) --synth stein --snr 30,25,20
	./$(BUILD)/fracterra_accuracy $(ACCURACY_FLAGS) --synth stein --snr 30 --z-only
	./$(BUILD)/fracterra_accuracy $(ACCURACY_FLAGS) --synth exact,sra,fft
	./$(BUILD)/fracterra_accuracy $(ACCURACY_FLAGS) --synth exact --jitter
	./$(BUILD)/fracterra_accuracy_reconstruct $(ACCURACY_RECON_FLAGS)
	./$(BUILD)/fracterra_accuracy_profile $(ACCURACY_PROFILE_FLAGS)
	./$(BUILD)/fracterra_accuracy_recon_structure --seeds 3 --dims 2.2,2.3,2.4,2.5,2.6,2.7,2.8 --synth exact
	./$(BUILD)/fracterra_accuracy_recon_structure --seeds 3 --dims 2.2,2.5,2.8 --synth sra
	./$(BUILD)/fracterra_accuracy_recon_structure --seeds 3 --dims 2.2,2.5,2.8 --synth sra --methods fractal --sigma0 surface
	./$(BUILD)/fracterra_accuracy_recon_structure --seeds 3 --dims 2.2,2.3,2.4,2.5,2.6,2.7,2.8 --synth sra --every 0 --fraction 0.11 --methods conditional,fractal
	./$(BUILD)/fracterra_accuracy_clarke --seeds 16 tests/data/dem_jacksboro_3s.tif tests/data/dem_volcano_maunga_whau_10m.tif \
	    tests/data/dem_luxembourg_terra_30s.tif tests/data/dem_luxembourg_utm32n.tif tests/data/dem_topobathy_bc_2min.tif
	./$(BUILD)/fracterra_accuracy_synth_dim --size 256 --seeds 41
	./$(BUILD)/fracterra_accuracy_synth_dim --size 1024 --seeds 7 --methods fft,sra,midpoint --dims 2.1,2.2,2.3

install: build
	cmake --install $(BUILD)

clean:
	rm -rf $(BUILD) out

# libFuzzer harnesses (fuzz/, clang + ASan + UBSan): each runs FUZZ_SECONDS from its seed corpus
# (fuzz/corpus/<target>/); a finding fails the run and leaves its reproducer in $(FUZZ_BUILD)/findings/.
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 600
FUZZ_TARGETS ?= points_text text_chains clarke_json urban_table cli_options gdal_vector gdal_raster
.PHONY: fuzz fuzz-build
fuzz-build: deps
	@CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFT_FUZZ=ON -DFT_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))

fuzz: fuzz-build
	bash scripts/run-fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)
