// The CUDA twin of the particle step: launches of core/physics/particles.h.
//
// The bin is a counting sort with no sort of keys: each live particle counts itself into its cell
// (an integer atomic, which also hands it a place among its cell's in arrival order), a scan of
// the counts gives every cell's start, each particle writes itself to its arrival place, and then
// takes its final place by counting the particles of its cell that come before it in ascending
// slot order. So every cell holds its slots in ascending order, exactly as the CPU reference's
// stable counting sort leaves them, whatever order the atomics ran in. The counts go back to zero
// for the cells that were touched, so no step clears the whole table.
//
// A step in a scene runs whole, in four launches and CUB's scan: the thread that counts a slot
// into its cell first emits the new particle the slot receives (or ages it, if the suction took
// it), and the thread that sums a living particle's pairs then moves it. Each of its launches may
// be scheduled while the one before it runs (programmatic dependent launch, on sm_90 and later).
// The phases on their own (the benchmarks', the tests') launch one by one.
//
// A frame of few particles (a scene's) runs in one launch, on one cluster of blocks that wait for
// each other where the step's launches would end (frame_in_one_cluster). Any other frame's steps
// run as one CUDA graph: hundreds of steps of small launches cost their launch overhead, not their
// arithmetic, when the host issues each one. The graph's launches read their
// step's arguments from the step list on the device, so the same graph serves every frame whose
// shape (steps, grid sizes, buffers) is the same; the host copies the list there, through pinned
// memory, before launching it.
#include <cooperative_groups.h>
#include <cub/block/block_scan.cuh>
#include <cub/device/device_scan.cuh>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/physics/particles.h"
#include "kernels/cuda_check.h"

namespace bleedsim {
namespace {

constexpr int kThreads = 256;
// A frame of few particles runs in one thread-block cluster (see frame_in_one_cluster): the most
// blocks a portable cluster holds, each thread scanning kScanItems cells' counts at a time. Blocks
// of 512 threads, not 1,024: on an H200 the default scene's frame took 5.52 ms so, 5.72 with 1,024.
constexpr int kClusterBlocks = 8;
constexpr int kClusterThreads = 512;
constexpr int kScanItems = 4;
// The most live particles, and cells, of a frame that runs in one cluster: two particles a thread
// (a bound, not a measured crossing: the scenes timed, a few thousand live, run faster so than as
// graphs), and two passes of a block's scan.
constexpr int kClusterMostLive = 2 * kClusterBlocks * kClusterThreads;
constexpr std::uint32_t kClusterMostCells = 2 * kClusterBlocks * kClusterThreads * kScanItems;

int blocks_for(int count) { return (count + kThreads - 1) / kThreads; }

// Where a kernel finds its step's arguments: given with the launch (a step launched on its own), or
// in the step list on the device (a step of a graph, whose launches stay the same from frame to frame).
struct GivenArgs {
  ParticleArgs a;
  __device__ ParticleArgs at(ParticlePhase) const { return a; }
};

struct PlannedArgs {
  ParticleArgs base;
  const ParticleStep* steps;
  const Emitter* emitters;
  int s;
  __device__ ParticleArgs at(ParticlePhase phase) const { return args_at(base, steps[s], emitters, phase); }
};

// Hopper's programmatic dependent launch: a kernel of a whole step may be scheduled while the kernel
// before it still runs, and waits here, before it reads anything, for that kernel to finish and
// its writes to be seen. Only the launch's latency overlaps, never the work. (Code compiled for an
// older GPU has no wait, and is then launched as usual: see launch.)
__device__ void wait_for_the_kernel_before() {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
  cudaGridDependencySynchronize();
#endif
}

template <class Args>
__global__ void emit_kernel(Args args) {
  const ParticleArgs a = args.at(ParticlePhase::emit);
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < a.new_count) emit_particle(a, t);
}

// The bin's storage in the particle scratch's sort_scratch: per cell a count (zero between steps),
// per live particle its place among its cell's in arrival order, the cells' particles in arrival
// order, and the scan's temporary storage.
struct BinScratch {
  std::uint32_t* count;      // cells + 1 (the last stays 0, so the scan's last entry is the total)
  std::uint32_t* part_count; // per part of the cells a cluster's block scans: its particles (zero between steps)
  std::uint32_t* arrival;    // per live particle t
  std::uint32_t* unordered;  // per sorted position: the t that arrived there
  void* scan;
  std::size_t scan_bytes;
};

std::size_t aligned(std::size_t bytes) { return (bytes + 255) / 256 * 256; }

std::size_t scan_bytes_for(std::uint32_t cells, cudaStream_t stream = nullptr) {
  std::size_t bytes = 0;
  BLEEDSIM_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, static_cast<std::uint32_t*>(nullptr),
                                                    static_cast<std::uint32_t*>(nullptr), int(cells) + 1, stream));
  return bytes;
}

BinScratch bin_scratch(const ParticleArrays& p, std::uint32_t cells) {
  char* at = static_cast<char*>(p.sort_scratch);
  BinScratch b{};
  b.count = reinterpret_cast<std::uint32_t*>(at);
  at += aligned((std::size_t(cells) + 1) * sizeof(std::uint32_t));
  b.part_count = reinterpret_cast<std::uint32_t*>(at);
  at += aligned(kClusterBlocks * sizeof(std::uint32_t));
  b.arrival = reinterpret_cast<std::uint32_t*>(at);
  at += aligned(std::size_t(p.capacity) * sizeof(std::uint32_t));
  b.unordered = reinterpret_cast<std::uint32_t*>(at);
  at += aligned(std::size_t(p.capacity) * sizeof(std::uint32_t));
  b.scan = at;
  b.scan_bytes = p.sort_scratch_bytes - std::size_t(at - static_cast<char*>(p.sort_scratch));
  return b;
}

// The t-th live slot (ascending) counts itself into its cell (its key, returned); the dead and
// aspirated count nowhere. In a whole step the thread that owns the slot first emits the new
// particle it receives, or ages it if the suction took it (the step's emit, and the integrate of
// the dead, in the bin's launch).
template <class Args, bool kWholeStep>
__device__ std::uint32_t count_into_cell(const Args& args, const BinScratch& b, int t) {
  const ParticleArgs a = args.at(ParticlePhase::bin);
  const int slot = nth_live_slot_ascending(a, t);
  if (kWholeStep) {
    const ParticleArgs emitting = args.at(ParticlePhase::emit);
    const int e = new_particle_in(emitting, std::size_t(slot));
    if (e < emitting.new_count) emit_particle(emitting, e);
    else age_aspirated(a.arrays, a.model, slot);
  }
  const std::uint32_t key = cell_key_of(a.arrays, a.model, slot);
  a.arrays.cell_key[t] = key;
  if (key != sentinel_key(a.model)) b.arrival[t] = atomicAdd(&b.count[key], 1u);
  return key;
}

template <class Args, bool kWholeStep>
__global__ void count_kernel(Args args, BinScratch b) {
  wait_for_the_kernel_before();
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < args.at(ParticlePhase::bin).live_count) count_into_cell<Args, kWholeStep>(args, b, t);
}

// Each particle at its arrival place in its cell's range; its cell's count back to zero (every
// particle of the cell writes the same zero, after the scan has read the count).
template <class Args>
__device__ void arrive(const Args& args, const BinScratch& b, int t) {
  const ParticleArgs a = args.at(ParticlePhase::bin);
  const std::uint32_t key = a.arrays.cell_key[t];
  if (key == sentinel_key(a.model)) return;
  b.unordered[a.arrays.cell_start[key] + b.arrival[t]] = std::uint32_t(t);
  b.count[key] = 0u;
}

template <class Args>
__global__ void arrive_kernel(Args args, BinScratch b) {
  wait_for_the_kernel_before();
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < args.at(ParticlePhase::bin).live_count) arrive(args, b, t);
}

// Each particle's final place: its cell's start plus the particles of its cell before it in
// ascending slot order (smaller t); there it writes its key and slot and gathers its sorted copies.
// Sorted positions past the living (aspirated or expired particles in the live range) get the
// largest key, as on the CPU.
template <class Args>
__device__ void take_place(const Args& args, const BinScratch& b, int t) {
  const ParticleArgs a = args.at(ParticlePhase::bin);
  const ParticleArrays& p = a.arrays;
  const std::uint32_t none = sentinel_key(a.model);
  if (std::uint32_t(t) >= p.cell_start[none]) p.sorted_key[t] = none;
  const std::uint32_t key = p.cell_key[t];
  if (key == none) return;
  const std::uint32_t start = p.cell_start[key], end = p.cell_start[key + 1];
  std::uint32_t i = start;
  for (std::uint32_t j = start; j < end; ++j) i += b.unordered[j] < std::uint32_t(t) ? 1u : 0u;
  p.sorted_key[i] = key;
  p.sorted_slot[i] = std::uint32_t(nth_live_slot_ascending(a, t));
  gather_sorted(p, a.model, int(i));
}

template <class Args>
__global__ void place_kernel(Args args, BinScratch b) {
  wait_for_the_kernel_before();
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < args.at(ParticlePhase::bin).live_count) take_place(args, b, t);
}

// A film with depth's depth at each sorted particle, and its parcels' weight on each node of the
// contact line's grid, once all are in their places.
template <class Args>
__global__ void depth_kernel(Args args) {
  wait_for_the_kernel_before();
  const ParticleArgs a = args.at(ParticlePhase::bin);
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < a.live_count) depth_particle(a.arrays, a.model, i);
  if (std::uint32_t(i) < line_node_count(a.model)) line_node_weight(a.arrays, a.model, std::uint32_t(i));
}

// In a whole step the living particle then moves at once: its pair sums are its own slot's, and no
// thread's collision reads anything but the sorted copies.
template <class Args, bool kWholeStep>
__device__ void collide(const Args& args, int i) {
  const ParticleArgs a = args.at(ParticlePhase::collide);
  collide_particle(a.arrays, a.model, i);
  if (kWholeStep && a.arrays.sorted_key[i] != sentinel_key(a.model))
    integrate_particle(a.arrays, a.model, int(a.arrays.sorted_slot[i]));
}

template <class Args, bool kWholeStep>
__global__ void collide_kernel(Args args) {
  wait_for_the_kernel_before();
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < args.at(ParticlePhase::collide).live_count) collide<Args, kWholeStep>(args, i);
}

template <class Args>
__global__ void integrate_kernel(Args args) {
  const ParticleArgs a = args.at(ParticlePhase::integrate);
  const int t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < a.live_count) integrate_particle(a.arrays, a.model, live_slot(a, t));
}

// A frame's steps in one launch, on one thread-block cluster: for a scene's frame, a few thousand
// particles on a panel's cells, whose step is a chain of short phases, each waiting for the one
// before. The phases are the whole step's, calling the same functions in the same order, each
// over every live particle; where a step's launches end, the cluster waits at its barrier (a
// hardware one, which also makes every write before it seen after it), with no launch between.
// The scan of the counts is the cluster's: block r scans part r of the cells, starting from the
// particles of the parts before it, which the count phase tallied.
__global__ void __launch_bounds__(kClusterThreads, 1) frame_in_one_cluster(PlannedArgs args, int steps, BinScratch b) {
#if defined(__CUDA_ARCH__) && __CUDA_ARCH__ >= 900
  using Scan = cub::BlockScan<std::uint32_t, kClusterThreads>;
  __shared__ typename Scan::TempStorage scan;
  __shared__ std::uint32_t part_count_here[kClusterBlocks];
  const cooperative_groups::cluster_group cluster = cooperative_groups::this_cluster();
  // Its barriers order the phases only across one cluster of all its blocks: a launch that is not
  // one would race silently, so it stops here instead.
  if (cluster.num_blocks() != unsigned(kClusterBlocks) || gridDim.x != unsigned(kClusterBlocks)) __trap();
  const std::uint32_t entries = cell_count(args.base.model) + 1;
  const std::uint32_t part = (entries + kClusterBlocks - 1) / kClusterBlocks;
  const std::uint32_t begin = umin(entries, blockIdx.x * part), end = umin(entries, begin + part);
  for (args.s = 0; args.s < steps; ++args.s) {
    // Each block takes an equal share of the live particles, so that every multiprocessor works.
    const int live = args.at(ParticlePhase::bin).live_count;
    const int share = (live + kClusterBlocks - 1) / kClusterBlocks;
    const int first = int(blockIdx.x) * share + int(threadIdx.x), past = min(live, (int(blockIdx.x) + 1) * share);
    if (threadIdx.x < kClusterBlocks) part_count_here[threadIdx.x] = 0u;
    __syncthreads();
    for (int t = first; t < past; t += kClusterThreads) {
      const std::uint32_t key = count_into_cell<PlannedArgs, true>(args, b, t);
      if (key != sentinel_key(args.base.model)) atomicAdd(&part_count_here[key / part], 1u);
    }
    __syncthreads();
    if (threadIdx.x < kClusterBlocks && part_count_here[threadIdx.x] > 0u)
      atomicAdd(&b.part_count[threadIdx.x], part_count_here[threadIdx.x]);
    cluster.sync();

    std::uint32_t before = 0;
    for (unsigned r = 0; r < blockIdx.x; ++r) before += b.part_count[r];
    for (std::uint32_t tile = begin; tile < end; tile += kClusterThreads * kScanItems) {
      const std::uint32_t c = tile + threadIdx.x * kScanItems;
      std::uint32_t counts[kScanItems], starts[kScanItems], tile_count = 0;
      for (int k = 0; k < kScanItems; ++k) counts[k] = c + k < end ? b.count[c + k] : 0u;
      Scan(scan).ExclusiveSum(counts, starts, tile_count);
      for (int k = 0; k < kScanItems; ++k)
        if (c + k < end) args.base.arrays.cell_start[c + k] = before + starts[k];
      before += tile_count;
      __syncthreads();  // the scan's storage, again
    }
    cluster.sync();

    if (blockIdx.x == 0 && threadIdx.x < kClusterBlocks) b.part_count[threadIdx.x] = 0u;  // all read them
    for (int t = first; t < past; t += kClusterThreads) arrive(args, b, t);
    cluster.sync();
    for (int t = first; t < past; t += kClusterThreads) take_place(args, b, t);
    cluster.sync();
    if (has_depth(args.base.model)) {
      const ParticleArrays& sorted = args.at(ParticlePhase::bin).arrays;
      for (int i = first; i < past; i += kClusterThreads) depth_particle(sorted, args.base.model, i);
      const std::uint32_t nodes = line_node_count(args.base.model);
      for (std::uint32_t n = blockIdx.x * kClusterThreads + threadIdx.x; n < nodes; n += kClusterBlocks * kClusterThreads)
        line_node_weight(sorted, args.base.model, n);
      cluster.sync();
    }
    for (int i = first; i < past; i += kClusterThreads) collide<PlannedArgs, true>(args, i);
    cluster.sync();
  }
#endif
}

// Every cell's start (and, past the last, the living's count) from the counts.
void scan_counts(const ParticleArrays& p, const ParticleModel& m, const BinScratch& b, cudaStream_t stream) {
  std::size_t bytes = b.scan_bytes;
  BLEEDSIM_CUDA_CHECK(cub::DeviceScan::ExclusiveSum(b.scan, bytes, b.count, p.cell_start, int(cell_count(m)) + 1, stream));
}

// Whether this build's particle kernels were compiled for sm_90 or later, not JIT-compiled from the
// older PTX (all of them alike: one translation unit, one list of architectures): only then does
// each kernel of a whole step wait for the kernel before it, and has the cluster's frame a body.
bool kernels_built_for_hopper() {
  static const bool built = [] {
    cudaFuncAttributes compiled{};
    BLEEDSIM_CUDA_CHECK(cudaFuncGetAttributes(&compiled, collide_kernel<PlannedArgs, true>));
    return compiled.ptxVersion >= 90;
  }();
  return built;
}

cudaLaunchConfig_t launch_config(int blocks, int threads, cudaStream_t stream, cudaLaunchAttribute* attributes,
                                 unsigned attribute_count) {
  cudaLaunchConfig_t config{};
  config.gridDim = dim3(unsigned(blocks));
  config.blockDim = dim3(unsigned(threads));
  config.stream = stream;
  config.attrs = attributes;
  config.numAttrs = attribute_count;
  return config;
}

// kernel<<<blocks, kThreads, 0, stream>>>(args...), in a whole step allowed to start while the
// launch before it finishes (wait_for_the_kernel_before).
template <bool kWholeStep, class... P, class... A>
void launch(void (*kernel)(P...), const char* name, int blocks, cudaStream_t stream, const A&... args) {
  cudaLaunchAttribute overlap{};
  overlap.id = cudaLaunchAttributeProgrammaticStreamSerialization;
  overlap.val.programmaticStreamSerializationAllowed = 1;
  const cudaLaunchConfig_t config =
      launch_config(blocks, kThreads, stream, &overlap, kWholeStep && kernels_built_for_hopper() ? 1 : 0);
  BLEEDSIM_CUDA_CHECK(cudaLaunchKernelEx(&config, kernel, args...));
  check_launch(name);
}

// The cluster's frame: one cluster of kClusterBlocks blocks.
cudaLaunchConfig_t one_cluster(cudaStream_t stream, cudaLaunchAttribute* cluster) {
  cluster->id = cudaLaunchAttributeClusterDimension;
  cluster->val.clusterDim.x = kClusterBlocks;
  cluster->val.clusterDim.y = 1;
  cluster->val.clusterDim.z = 1;
  return launch_config(kClusterBlocks, kClusterThreads, stream, cluster, 1);
}

// Whether this machine runs the cluster's frame: built for it, a cluster of its size fits, and
// BLEEDSIM_CUDA_FRAMES does not ask for graphs (compute-sanitizer's racecheck faults on the cluster's
// launch, inside the tool: docs/reliability.md).
bool frames_run_in_one_cluster() {
  static const bool runs = [] {
    const char* asked = std::getenv("BLEEDSIM_CUDA_FRAMES");
    const std::string frames = asked ? asked : "auto";
    if (frames != "auto" && frames != "graph")
      throw std::runtime_error("BLEEDSIM_CUDA_FRAMES=" + frames +
                               ": expected auto (small frames in one cluster) or graph");
    if (frames == "graph" || !kernels_built_for_hopper()) return false;
    cudaLaunchAttribute cluster{};
    const cudaLaunchConfig_t config = one_cluster(nullptr, &cluster);
    int clusters = 0;
    const bool fits = cudaOccupancyMaxActiveClusters(&clusters, frame_in_one_cluster, &config) == cudaSuccess;
    cudaGetLastError();  // a refused query leaves its error behind; the frames then run as graphs
    return fits && clusters > 0;
  }();
  return runs;
}

// The steps of `f` in the cluster's frame.
void launch_in_one_cluster(const ParticleSteps& f, cudaStream_t stream) {
  cudaLaunchAttribute cluster{};
  const cudaLaunchConfig_t config = one_cluster(stream, &cluster);
  const PlannedArgs args{f.base, f.device_steps, f.device_emitters, 0};
  BLEEDSIM_CUDA_CHECK(cudaLaunchKernelEx(&config, frame_in_one_cluster, args, f.count,
                                         bin_scratch(f.base.arrays, cell_count(f.base.model))));
  check_launch("frame_in_one_cluster");
}

// The bin's launches over `live_threads` threads; `shape` gives the arrays and the model.
template <class Args, bool kWholeStep>
void launch_bin(const Args& args, const ParticleArgs& shape, int live_threads, cudaStream_t stream) {
  const int blocks = blocks_for(live_threads);
  const BinScratch b = bin_scratch(shape.arrays, cell_count(shape.model));
  launch<kWholeStep>(count_kernel<Args, kWholeStep>, "count_kernel", blocks, stream, args, b);
  scan_counts(shape.arrays, shape.model, b, stream);
  launch<kWholeStep>(arrive_kernel<Args>, "arrive_kernel", blocks, stream, args, b);
  launch<kWholeStep>(place_kernel<Args>, "place_kernel", blocks, stream, args, b);
  if (has_depth(shape.model)) {
    const int film_blocks = std::max(blocks, blocks_for(int(line_node_count(shape.model))));
    launch<kWholeStep>(depth_kernel<Args>, "depth_kernel", film_blocks, stream, args);
  }
}

// One phase on its own (the default stream): each its own launches.
void launch_phase(ParticlePhase phase, const ParticleArgs& a) {
  const GivenArgs args{a};
  const int new_blocks = blocks_for(a.new_count), live_blocks = blocks_for(a.live_count);
  switch (phase) {
    case ParticlePhase::emit:
      if (new_blocks == 0) return;
      launch<false>(emit_kernel<GivenArgs>, "emit_kernel", new_blocks, nullptr, args);
      break;
    case ParticlePhase::bin:
      if (live_blocks > 0) launch_bin<GivenArgs, false>(args, a, a.live_count, nullptr);
      break;
    case ParticlePhase::collide:
      if (live_blocks == 0) return;
      launch<false>(collide_kernel<GivenArgs, false>, "collide_kernel", live_blocks, nullptr, args);
      break;
    case ParticlePhase::integrate:
      if (live_blocks == 0) return;
      launch<false>(integrate_kernel<GivenArgs>, "integrate_kernel", live_blocks, nullptr, args);
      break;
  }
}

// A whole step (emit, bin, collide, integrate) over `live_threads` threads, in four launches and
// CUB's scan: emission and the dead's ageing ride in the bin's first launch, the living's
// integration in the collision's. The same bytes as the phases one by one (core/physics/particles.h
// says which slots each touches).
void launch_step(const PlannedArgs& args, int live_threads, cudaStream_t stream) {
  if (live_threads == 0) return;
  launch_bin<PlannedArgs, true>(args, args.base, live_threads, stream);
  launch<true>(collide_kernel<PlannedArgs, true>, "collide_kernel", blocks_for(live_threads), stream, args);
}

// Threads for `count` elements in a graph that must serve later frames too: a power of two, at least
// `least`, at most the ring (0 when none), so the graph changes only when a count outgrows its size.
int graph_threads(int count, int least, int capacity) {
  if (count == 0) return 0;
  int threads = least;
  while (threads < count) threads *= 2;
  return std::min(threads, capacity);
}

// What a graph's launches depend on besides the device step list's contents.
struct GraphShape {
  const float* position = nullptr;  // the stage's arrays (the model is the stage's, fixed)
  const ParticleStep* steps = nullptr;
  const Emitter* emitters = nullptr;
  int count = 0;
  int live_threads = 0;
  bool operator==(const GraphShape& o) const {
    return position == o.position && steps == o.steps && emitters == o.emitters && count == o.count &&
           live_threads == o.live_threads;
  }
};

// The steps' graph and what feeds it: a stream of its own (a blocking one: it waits for the work
// issued before it on the default stream, and that stream's later work waits for it) and two
// pinned staging buffers, used in turn, so that copying one run's steps need not wait for the
// copy before it.
class StepGraph final : public TwinCache {
 public:
  StepGraph() {
    BLEEDSIM_CUDA_CHECK(cudaStreamCreate(&stream_));
    frames_run_in_one_cluster();  // asked here, not first while a graph is being captured
  }
  ~StepGraph() override {
    if (exec_) cudaGraphExecDestroy(exec_);
    for (Staging& s : staging_) {
      if (s.copied) cudaEventDestroy(s.copied);
      if (s.host) cudaFreeHost(s.host);
    }
    cudaStreamDestroy(stream_);
  }
  StepGraph(const StepGraph&) = delete;
  StepGraph& operator=(const StepGraph&) = delete;

  void run(const ParticleSteps& f) {
    copy_to_device(f);
    int most_live = 0;
    for (int s = 0; s < f.count; ++s) most_live = std::max(most_live, f.steps[s].live_count);
    if (most_live <= kClusterMostLive && cell_count(f.base.model) < kClusterMostCells && frames_run_in_one_cluster()) {
      launch_in_one_cluster(f, stream_);
      return;
    }
    if (f.count == 1) {  // a step on its own (between the instrument's): its launches, directly
      launch_step(PlannedArgs{f.base, f.device_steps, f.device_emitters, 0}, f.steps[0].live_count, stream_);
      return;
    }
    const GraphShape shape{f.base.arrays.position, f.device_steps, f.device_emitters, f.count,
                           graph_threads(most_live, 16 * kThreads, f.base.arrays.capacity)};
    if (!exec_ || !(shape == shape_)) capture(f, shape);
    BLEEDSIM_CUDA_CHECK(cudaGraphLaunch(exec_, stream_));
  }

 private:
  struct Staging {
    void* host = nullptr;
    std::size_t bytes = 0;
    cudaEvent_t copied = nullptr;  // recorded after the last copy out of it
  };

  // The steps, and the emitters they use, to the same places on the device.
  void copy_to_device(const ParticleSteps& f) {
    const ParticleStep& last = f.steps[f.count - 1];
    const std::uint32_t first_emitter = f.steps[0].first_emitter, end_emitter = last.first_emitter + last.emitter_count;
    const std::size_t step_bytes = std::size_t(f.count) * sizeof(ParticleStep);
    const std::size_t emitter_bytes = std::size_t(end_emitter - first_emitter) * sizeof(Emitter);
    Staging& s = staging_[next_];
    next_ = 1 - next_;
    if (s.copied) BLEEDSIM_CUDA_CHECK(cudaEventSynchronize(s.copied));
    else BLEEDSIM_CUDA_CHECK(cudaEventCreateWithFlags(&s.copied, cudaEventDisableTiming));
    if (s.bytes < step_bytes + emitter_bytes) {
      if (s.host) BLEEDSIM_CUDA_CHECK(cudaFreeHost(s.host));
      s.host = nullptr;
      s.bytes = 0;
      BLEEDSIM_CUDA_CHECK(cudaMallocHost(&s.host, 2 * (step_bytes + emitter_bytes)));
      s.bytes = 2 * (step_bytes + emitter_bytes);
    }
    char* staged = static_cast<char*>(s.host);
    std::memcpy(staged, f.steps, step_bytes);
    BLEEDSIM_CUDA_CHECK(cudaMemcpyAsync(f.device_steps, staged, step_bytes, cudaMemcpyHostToDevice, stream_));
    if (emitter_bytes > 0) {
      std::memcpy(staged + step_bytes, f.emitters + first_emitter, emitter_bytes);
      BLEEDSIM_CUDA_CHECK(cudaMemcpyAsync(f.device_emitters + first_emitter, staged + step_bytes, emitter_bytes,
                                          cudaMemcpyHostToDevice, stream_));
    }
    BLEEDSIM_CUDA_CHECK(cudaEventRecord(s.copied, stream_));
  }

  // Records every step's launches into a graph, reading each step's arguments from the device list.
  void capture(const ParticleSteps& f, const GraphShape& shape) {
    cudaGraph_t graph = nullptr;
    BLEEDSIM_CUDA_CHECK(cudaStreamBeginCapture(stream_, cudaStreamCaptureModeThreadLocal));
    try {
      for (int s = 0; s < f.count; ++s)
        launch_step(PlannedArgs{f.base, f.device_steps, f.device_emitters, s}, shape.live_threads, stream_);
    } catch (...) {
      if (cudaStreamEndCapture(stream_, &graph) == cudaSuccess && graph) cudaGraphDestroy(graph);
      throw;
    }
    BLEEDSIM_CUDA_CHECK(cudaStreamEndCapture(stream_, &graph));
    // A graph of the same kernels in the same order, with other sizes or buffers, updates the one
    // there is, at a fraction of making a new one; other kernels (another number of steps, steps
    // with no particles, CUB's choice for other items) need a new one. Which it is, is decided
    // here rather than by a failed update, which tools such as compute-sanitizer report as errors.
    const std::unique_ptr<CUgraph_st, cudaError_t (*)(cudaGraph_t)> owned(graph, cudaGraphDestroy);
    std::vector<const void*> kernels = kernels_of(graph);
    bool updated = false;
    if (exec_ && kernels == kernels_) {
      cudaGraphExecUpdateResultInfo update{};
      updated = cudaGraphExecUpdate(exec_, graph, &update) == cudaSuccess;
      if (!updated) cudaGetLastError();  // not expected of the same kernels; a new graph will do
    }
    if (!updated) {
      kernels_.clear();
      if (exec_) cudaGraphExecDestroy(exec_);
      exec_ = nullptr;
      const cudaError_t made = cudaGraphInstantiate(&exec_, graph, 0);
      if (made != cudaSuccess) exec_ = nullptr;
      BLEEDSIM_CUDA_CHECK(made);
    }
    kernels_ = std::move(kernels);
    shape_ = shape;
  }

  // The kernel of each node of a captured graph (a stream's capture is a chain, in launch order).
  static std::vector<const void*> kernels_of(cudaGraph_t graph) {
    std::size_t count = 0;
    BLEEDSIM_CUDA_CHECK(cudaGraphGetNodes(graph, nullptr, &count));
    std::vector<cudaGraphNode_t> nodes(count);
    BLEEDSIM_CUDA_CHECK(cudaGraphGetNodes(graph, nodes.data(), &count));
    std::vector<const void*> kernels;
    kernels.reserve(count);
    for (cudaGraphNode_t node : nodes) {
      cudaGraphNodeType type{};
      BLEEDSIM_CUDA_CHECK(cudaGraphNodeGetType(node, &type));
      cudaKernelNodeParams params{};
      if (type == cudaGraphNodeTypeKernel) BLEEDSIM_CUDA_CHECK(cudaGraphKernelNodeGetParams(node, &params));
      kernels.push_back(params.func);
    }
    return kernels;
  }

  cudaStream_t stream_ = nullptr;
  Staging staging_[2];
  int next_ = 0;
  cudaGraphExec_t exec_ = nullptr;
  std::vector<const void*> kernels_;  // exec_'s
  GraphShape shape_;
};

}  // namespace

std::size_t particle_sort_scratch_cuda(int capacity, std::uint32_t cells) {
  return aligned((std::size_t(cells) + 1) * sizeof(std::uint32_t)) + aligned(kClusterBlocks * sizeof(std::uint32_t)) +
         2 * aligned(std::size_t(capacity) * sizeof(std::uint32_t)) + scan_bytes_for(cells);
}

void cuda_twin(ParticlePhase phase, const ParticleArgs& a) {
  launch_phase(phase, a);
}

void cuda_twin(const ParticleSteps& f) {
  if (f.count == 0) return;
  if (!*f.cache) *f.cache = std::make_unique<StepGraph>();
  static_cast<StepGraph&>(**f.cache).run(f);
}

}  // namespace bleedsim
