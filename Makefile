# omnicam — top-level entry points. `make demo` and `make test` each do all set-up themselves.
BUILD_DIR ?= build
FUZZ_DIR  ?= $(BUILD_DIR)/fuzz-asan
JOBS      ?= $(shell nproc)
FUZZ_SECONDS ?= 60
SUDO      := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

# Every Debian 12 package the project needs (build, tests, demo, benchmarks).
DEBIAN_PACKAGES := build-essential cmake pkg-config python3 \
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev zlib1g-dev \
  libpng-dev libjpeg-dev libtiff-dev \
  libeigen3-dev nlohmann-json3-dev libcli11-dev libssl-dev bc \
  libgtest-dev libgmock-dev libbenchmark-dev libopencv-dev libopencv-contrib-dev \
  povray blender blender-data python3-numpy python3-matplotlib libtinygltf-dev \
  pybind11-dev python3-dev python3-pytest python3-yaml python3-pil mypy \
  clang libfuzzer-14-dev libclang-rt-14-dev \
  slurmctld slurmd slurm-client munge libcgal-dev libapriltag-dev \
  python3-rosbag python3-sensor-msgs \
  python3-setuptools python3-wheel python3-pip python3-venv python3-build ccache \
  libroscpp-dev libimage-transport-dev libtf2-ros-dev librosbag-dev libcamera-info-manager-dev \
  libdiagnostic-updater-dev libimage-geometry-dev libsensor-msgs-dev libnav-msgs-dev \
  python3-rosmaster python3-rospy python3-rostopic python3-roslaunch python3-nav-msgs rosout \
  python3-diagnostic-msgs python3-tf2-msgs

.PHONY: deps build test demo bench clean fuzz-build fuzz

# Idempotent and non-interactive: apt runs only when a package is missing.
deps:
	@if dpkg-query -W -f='$${Status}\n' $(DEBIAN_PACKAGES) 2>/dev/null | grep -qv '^install ok installed$$' \
	    || ! dpkg-query -W $(DEBIAN_PACKAGES) >/dev/null 2>&1; then \
	  echo "make deps: installing Debian packages"; \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get update -q && \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $(DEBIAN_PACKAGES); \
	else echo "make deps: all Debian packages present"; fi
	@# The Khronos glTF validator (npm), pinned by tools/gltf-validator/package-lock.json.
	@if [ ! -d tools/gltf-validator/node_modules/gltf-validator ]; then \
	  command -v npm >/dev/null || $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -q nodejs npm; \
	  npm ci --prefix tools/gltf-validator --no-audit --no-fund; \
	else echo "make deps: glTF validator present"; fi

$(BUILD_DIR)/CMakeCache.txt:
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD_DIR)/CMakeCache.txt
	cmake --build $(BUILD_DIR) -j $(JOBS)

# The libFuzzer targets (clang, ASan + UBSan) in their own build folder; make test runs each for
# 10 s ("fuzz smoke"), make fuzz for FUZZ_SECONDS each.
$(FUZZ_DIR)/CMakeCache.txt:
	cmake -S . -B $(FUZZ_DIR) -DOMNICAM_FUZZ=ON -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo

fuzz-build: deps $(FUZZ_DIR)/CMakeCache.txt
	cmake --build $(FUZZ_DIR) -j $(JOBS)

fuzz: fuzz-build
	@for t in scene_loader gltf_import sidecar dataset_spec manifest shard_manifest exr_frame image; do \
	  fuzz/run_fuzzer.sh $(FUZZ_DIR)/bin/fuzz_$$t $(FUZZ_SECONDS) $$t || exit 1; done

test: build fuzz-build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The demo needs the omnicam binary only: not the test programs, benchmarks or the Python module.
demo: deps $(BUILD_DIR)/CMakeCache.txt
	cmake --build $(BUILD_DIR) -j $(JOBS) --target omnicam
	@status=0; $(BUILD_DIR)/bin/omnicam demo -o out/demo || status=$$?; \
	  if [ $$status = 0 ] || [ $$status -ge 64 -a $$status -le 127 ]; then \
	    echo "make demo: the report is $(CURDIR)/out/demo/index.html"; fi; exit $$status

# Frames/s of the fast renderer, fast vs POV-Ray per frame over the 100-frame thesis-loop (1 and
# 16 spp), what a dataset frame costs and a 1000-frame dataset with all outputs against RGB only,
# frames/s against scene size, a POV-Ray dataset on Slurm (2 tasks x 1 thread vs 1 x 2), and the
# Python bindings (a Python render loop against the same loop in C++; project of 10^6 points).
bench: build
	$(BUILD_DIR)/bin/omnicam_bench --benchmark_counters_tabular=true
	$(BUILD_DIR)/bin/omnicam bench --json
	$(BUILD_DIR)/bin/path_vs_cycles
	$(BUILD_DIR)/bin/path_dataset_rate
	bench/povray_ratio.sh 1 100
	bench/povray_ratio.sh 16 100
	$(BUILD_DIR)/bin/dataset_bench
	bench/dataset_ratio.sh 1000
	mkdir -p out && $(BUILD_DIR)/bin/scene_scaling --csv out/scaling.csv
	$(BUILD_DIR)/bin/slurm_speedup --csv out/slurm_speedup.csv
	$(BUILD_DIR)/bin/ros_latency
	PYTHONPATH=$(BUILD_DIR)/python /usr/bin/python3 bench/python_bench.py

clean:
	rm -rf $(BUILD_DIR) out
