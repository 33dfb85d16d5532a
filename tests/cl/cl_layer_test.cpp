// The OpenCL layer: device listing and choice, include expansion, build errors with logs,
// and per-pass profiling.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "cl/error.h"
#include "cl/kernel_args.h"
#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "support/cl_fixture.h"

namespace {

namespace fs = std::filesystem;

// Points ROLYPOLY_KERNEL_DIR at a temporary folder for the lifetime of the object.
struct TempKernelDir {
  fs::path dir;
  TempKernelDir() {
    dir = fs::temp_directory_path() / ("rolypoly_kernels_" + std::to_string(::getpid()));
    fs::create_directories(dir / "shared");
    setenv("ROLYPOLY_KERNEL_DIR", dir.c_str(), 1);
  }
  ~TempKernelDir() {
    unsetenv("ROLYPOLY_KERNEL_DIR");
    fs::remove_all(dir);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
  }
};

TEST(Devices, ListsAtLeastOneDeviceWithSaneProperties) {
  auto devices = rp::cl::list_devices();
  ASSERT_FALSE(devices.empty());
  for (size_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].index, int(i));
    EXPECT_FALSE(devices[i].name.empty());
    EXPECT_GT(devices[i].compute_units, 0u);
    EXPECT_GT(devices[i].global_mem_bytes, 0u);
    EXPECT_NE(devices[i].version.find("OpenCL"), std::string::npos);
  }
}

TEST(Devices, CpuSpansFollowTheNativeFloatWidth) {
  // The span kernels' lanes per work-item on a CPU (rp::cl::cpu_span_lanes): 16 where the
  // registers hold 16 floats (AVX-512), 8 otherwise (AVX2: 8; narrower CPUs still get 8, the
  // narrowest span the CPU layouts support).
  rp::cl::DeviceInfo d;
  for (uint32_t width : {1u, 4u, 8u}) {
    d.native_float_width = width;
    EXPECT_EQ(rp::cl::cpu_span_lanes(d), 8) << width;
  }
  for (uint32_t width : {16u, 32u}) {
    d.native_float_width = width;
    EXPECT_EQ(rp::cl::cpu_span_lanes(d), 16) << width;
  }
  // Every listed device reports its native width (OpenCL requires at least 1).
  for (const rp::cl::DeviceInfo& device : rp::cl::list_devices())
    EXPECT_GE(device.native_float_width, 1u) << device.name;
}

TEST(Devices, ChoiceByIndexNameAndDefault) {
  auto devices = rp::cl::list_devices();
  EXPECT_EQ(rp::cl::choose_device("0").name, devices[0].name);
  // A case-flipped substring of the name still matches.
  std::string part = devices[0].name.substr(0, 4);
  for (char& c : part) c = char(std::isupper(static_cast<unsigned char>(c)) ? std::tolower(c) : std::toupper(c));
  EXPECT_EQ(rp::cl::choose_device(part).name, devices[0].name);
  rp::cl::DeviceInfo def = rp::cl::choose_device("");
  bool any_gpu = std::any_of(devices.begin(), devices.end(), [](auto& d) { return d.is_gpu; });
  EXPECT_EQ(def.is_gpu, any_gpu);
}

TEST(Devices, UnknownDeviceIsAClearError) {
  try {
    rp::cl::choose_device("no-such-device-anywhere");
    FAIL() << "expected an error";
  } catch (const rp::cl::Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("no-such-device-anywhere"), std::string::npos);
    EXPECT_NE(msg.find("[0]"), std::string::npos) << "the message should list the devices";
  }
  EXPECT_THROW(rp::cl::choose_device("999"), rp::cl::Error);
}

TEST(KernelSource, ExpandsIncludesOnceWithLineMarkers) {
  TempKernelDir k;
  k.write("shared/a.h", "#define A 1\n");
  k.write("main.cl", "#include \"shared/a.h\"\n#include \"shared/a.h\"\nkernel void f() {}\n");
  std::string src = rp::cl::kernel_source("main.cl");
  EXPECT_NE(src.find("#define A 1"), std::string::npos);
  EXPECT_EQ(src.find("#define A 1"), src.rfind("#define A 1")) << "included twice";
  EXPECT_NE(src.find("#line 1 \"shared/a.h\""), std::string::npos);
  EXPECT_THROW(rp::cl::kernel_source("missing.cl"), rp::cl::Error);
  k.write("bad.cl", "#include \"shared/nothere.h\"\n");
  EXPECT_THROW(rp::cl::kernel_source("bad.cl"), rp::cl::Error);
}

TEST(ProgramCache, BuildFailureCarriesTheBuildLog) {
  TempKernelDir k;
  k.write("broken.cl", "kernel void broken(global int* x) { x[0] = undeclared_name; }\n");
  rp::cl::ProgramCache cache(rp::test::context());
  try {
    cache.program("broken.cl");
    FAIL() << "expected a build error";
  } catch (const rp::cl::BuildError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("broken.cl"), std::string::npos);
    EXPECT_NE(msg.find("build log"), std::string::npos);
    EXPECT_NE(e.log().find("undeclared_name"), std::string::npos) << e.log();
  }
}

TEST(ProgramCache, BuildsOncePerFileAndOptions) {
  TempKernelDir k;
  k.write("ok.cl", "kernel void ok(global int* x) { x[get_global_id(0)] = VALUE; }\n");
  rp::cl::ProgramCache cache(rp::test::context());
  const cl::Program& a = cache.program("ok.cl", "-DVALUE=1");
  const cl::Program& b = cache.program("ok.cl", "-DVALUE=1");
  const cl::Program& c = cache.program("ok.cl", "-DVALUE=2");
  EXPECT_EQ(a(), b());
  EXPECT_NE(a(), c());
}

// A host call that binds fewer or more values than the kernel takes throws, naming the kernel;
// the values it binds reach the kernel in order (probe_fill writes (i, 1, 2, 3) below n).
TEST(ProgramCache, JoinsOptionsLeavingEmptyPartsOut) {
  EXPECT_EQ(rp::cl::join_options({}), "");
  EXPECT_EQ(rp::cl::join_options({"", ""}), "");
  EXPECT_EQ(rp::cl::join_options({"-DA=1", "", "-DB"}), "-DA=1 -DB");
  EXPECT_EQ(rp::cl::join_options({"", "-DRP_GI_SVO"}), "-DRP_GI_SVO");
}

TEST(KernelArgs, BindsInOrderAndRefusesAWrongCount) {
  auto& ctx = rp::test::context();
  ::cl::Kernel k = rp::test::programs().kernel("probe.cl", "probe_fill");
  ::cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, 4 * 16);
  for (size_t given : {size_t(1), size_t(3)}) {
    try {
      if (given == 1)
        rp::cl::bind_args(k, out);
      else
        rp::cl::bind_args(k, out, cl_uint(2), cl_uint(0));
      FAIL() << "bound " << given << " values to a kernel of two arguments";
    } catch (const rp::cl::Error& e) {
      EXPECT_EQ(std::string(e.what()), "kernel probe_fill takes 2 arguments but the host bound " +
                                           std::to_string(given));
    }
  }
  const float sentinel[16] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
  ctx.queue.enqueueWriteBuffer(out, CL_TRUE, 0, sizeof sentinel, sentinel);
  rp::cl::bind_args(k, out, cl_uint(2));
  ctx.queue.enqueueNDRangeKernel(k, ::cl::NullRange, ::cl::NDRange(4));
  float got[16];
  ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, sizeof got, got);
  EXPECT_EQ(got[0], 0.0f);
  EXPECT_EQ(got[4], 1.0f);
  EXPECT_EQ(got[7], 3.0f);
  EXPECT_EQ(got[8], -1.0f) << "item 2 is at n: not written";
}

TEST(Profiler, RecordsTimePerPassName) {
  TempKernelDir k;
  k.write("fill.cl", "kernel void fill(global int* x, int v) { x[get_global_id(0)] = v; }\n");
  rp::cl::ProgramCache cache(rp::test::context());
  cl::Kernel kernel = cache.kernel("fill.cl", "fill");
  cl::Buffer buf(rp::test::context().context, CL_MEM_READ_WRITE, 1024 * sizeof(int));
  kernel.setArg(0, buf);
  kernel.setArg(1, 7);
  rp::cl::Profiler profiler(rp::test::context().queue);
  profiler.enqueue("first", kernel, cl::NDRange(1024));
  profiler.enqueue("second", kernel, cl::NDRange(1024));
  profiler.enqueue("second", kernel, cl::NDRange(1024));
  rp::cl::PassTimes times = profiler.collect();
  ASSERT_EQ(times.size(), 2u);
  EXPECT_GE(times["first"], 0.0);
  EXPECT_GE(times["second"], 0.0);
  std::vector<int> host(1024);
  rp::test::context().queue.enqueueReadBuffer(buf, CL_TRUE, 0, host.size() * sizeof(int), host.data());
  EXPECT_EQ(host[1023], 7);
  EXPECT_TRUE(profiler.collect().empty()) << "collect() must clear the recorded events";
  EXPECT_THROW(profiler.enqueue("bad", kernel, cl::NDRange(1000), cl::NDRange(3000)), rp::cl::Error);
}

TEST(Profiler, TimestampCheckRejectsZeroShortAndOverlappingTimes) {
  using rp::cl::EventTimes;
  using rp::cl::timestamps_usable;
  const EventTimes a{10, 20, 1000, 5000}, b{11, 21, 5000, 9000};
  EXPECT_TRUE(timestamps_usable({a, b}, 100));
  EXPECT_FALSE(timestamps_usable({}, 100));
  EXPECT_FALSE(timestamps_usable({{0, 0, 0, 0}, {0, 0, 0, 0}}, 100)) << "rusticl: all zero";
  EXPECT_FALSE(timestamps_usable({{0, 0, 0, 1}}, 100)) << "zero start";
  EXPECT_FALSE(timestamps_usable({{1, 1, 7, 8}}, 100)) << "1 ns for 4 MiB: not a clock";
  EXPECT_FALSE(timestamps_usable({{1, 1, 9000, 5000}}, 100)) << "end before start";
  EXPECT_FALSE(timestamps_usable({b, a}, 100)) << "the second starts before the first ended";
}

TEST(Profiler, TimestampCheckKnowsPoclAndRusticl) {
  // PoCL's timestamps are usable; Mesa rusticl's (22.3) are zero: its passes are host-timed.
  const rp::cl::Context& c = rp::test::context();
  const rp::cl::Timing t = rp::cl::detect_timing(c.context, c.queue);
  if (c.info.platform_name.find("Portable Computing Language") != std::string::npos)
    EXPECT_EQ(t, rp::cl::Timing::kDevice);
  else if (c.info.platform_name.find("rusticl") != std::string::npos)
    EXPECT_EQ(t, rp::cl::Timing::kHost);
  else
    GTEST_SKIP() << "no expectation for " << c.info.platform_name << " ("
                 << rp::cl::timing_name(t) << " timing)";
}

TEST(Profiler, HostTimingFinishesEachLaunchAndTimesIt) {
  TempKernelDir k;
  k.write("spin.cl",
          "kernel void spin(global float* x, int n) { float v = x[get_global_id(0)];\n"
          "  for (int i = 0; i < n; ++i) v = v * 0.999f + 1.0f; x[get_global_id(0)] = v; }\n");
  rp::cl::ProgramCache cache(rp::test::context());
  cl::Kernel kernel = cache.kernel("spin.cl", "spin");
  cl::Buffer buf(rp::test::context().context, CL_MEM_READ_WRITE, 4096 * sizeof(float));
  rp::test::context().queue.enqueueFillBuffer(buf, 0.0f, 0, 4096 * sizeof(float));
  kernel.setArg(0, buf);
  kernel.setArg(1, 2000);
  rp::cl::Profiler profiler(rp::test::context().queue, rp::cl::Timing::kHost);
  EXPECT_EQ(profiler.timing(), rp::cl::Timing::kHost);
  profiler.enqueue("a", kernel, cl::NDRange(4096));
  profiler.enqueue("b", kernel, cl::NDRange(4096));
  profiler.enqueue("b", kernel, cl::NDRange(4096));
  cl::Event copy;
  cl::Buffer other(rp::test::context().context, CL_MEM_READ_WRITE, 4096 * sizeof(float));
  rp::test::context().queue.enqueueCopyBuffer(buf, other, 0, 0, 4096 * sizeof(float), nullptr,
                                              &copy);
  profiler.record("c", copy);
  rp::cl::PassTimes times = profiler.collect();
  ASSERT_EQ(times.size(), 3u);
  EXPECT_GT(times["a"], 0.0);
  EXPECT_GT(times["b"], 0.0);
  EXPECT_GE(times["c"], 0.0);
  EXPECT_TRUE(profiler.collect().empty());
  EXPECT_THROW(profiler.enqueue("bad", kernel, cl::NDRange(1000), cl::NDRange(3000)), rp::cl::Error);
}

}  // namespace
