// The global allocation functions of test_app, replaced by counting ones (see alloc_counter.h).
// The counter and the recorded call stacks are globals on purpose: operator new is global, and
// its replacement can only talk to the tests through global state.
#include "alloc_counter.h"

#include <cxxabi.h>
#include <dlfcn.h>
#include <execinfo.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <new>
#include <string>
#include <utility>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define RP_ALLOC_COUNTER 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RP_ALLOC_COUNTER 0
#endif
#endif
#ifndef RP_ALLOC_COUNTER
#define RP_ALLOC_COUNTER 1
#endif

namespace {

constexpr int kDepth = 20;          // call stack frames kept per allocation
constexpr size_t kMaxTraces = 8192;  // allocations recorded (~1.3 MB of return addresses)

struct Trace {
  void* frames[kDepth];
  int depth;
};

std::atomic<uint64_t> g_count{0};
std::atomic<bool> g_recording{false};
std::atomic<size_t> g_traces_used{0};
Trace g_traces[kMaxTraces];
thread_local bool t_in_hook = false;  // backtrace() must not record itself

[[maybe_unused]] void note_allocation() {
  g_count.fetch_add(1, std::memory_order_relaxed);
  if (!g_recording.load(std::memory_order_relaxed) || t_in_hook) return;
  t_in_hook = true;
  const size_t i = g_traces_used.fetch_add(1, std::memory_order_relaxed);
  if (i < kMaxTraces) g_traces[i].depth = backtrace(g_traces[i].frames, kDepth);
  t_in_hook = false;
}

[[maybe_unused]] void* allocate(std::size_t n) {
  note_allocation();
  if (void* p = std::malloc(n != 0 ? n : 1)) return p;
  throw std::bad_alloc();
}

[[maybe_unused]] void* allocate_aligned(std::size_t n, std::align_val_t align) {
  note_allocation();
  const std::size_t a = std::max(static_cast<std::size_t>(align), sizeof(void*));
  const std::size_t bytes = (std::max<std::size_t>(n, 1) + a - 1) / a * a;  // aligned_alloc rule
  if (void* p = std::aligned_alloc(a, bytes)) return p;
  throw std::bad_alloc();
}

// "ns::f(int, char) const" -> "ns::f": drops the trailing parameter list (and qualifiers).
std::string without_parameters(std::string name) {
  size_t end = name.rfind(')');
  if (end == std::string::npos) return name;
  int depth = 0;
  for (size_t i = end + 1; i-- > 0;) {
    if (name[i] == ')') ++depth;
    if (name[i] == '(' && --depth == 0) return name.substr(0, i);
  }
  return name;
}

// Function names for return addresses: addr2line for this executable (its functions are not
// in the dynamic symbol table), dladdr + demangling for shared libraries.
std::map<void*, std::string> symbolize(const std::vector<void*>& addresses) {
  std::map<void*, std::string> names;
  Dl_info self{};
  dladdr(reinterpret_cast<void*>(&symbolize), &self);
  std::vector<void*> in_exe;
  for (void* a : addresses) {
    Dl_info info{};
    if (dladdr(a, &info) != 0 && info.dli_fbase == self.dli_fbase) {
      in_exe.push_back(a);
      continue;
    }
    std::string name = "?";
    if (info.dli_sname != nullptr) {
      int status = 0;
      char* demangled = abi::__cxa_demangle(info.dli_sname, nullptr, nullptr, &status);
      name = status == 0 && demangled ? demangled : info.dli_sname;
      std::free(demangled);
    }
    std::string lib = info.dli_fname ? info.dli_fname : "?";
    names[a] = without_parameters(name) + " [" + lib.substr(lib.rfind('/') + 1) + "]";
  }
  for (size_t first = 0; first < in_exe.size(); first += 200) {
    const size_t last = std::min(in_exe.size(), first + 200);
    std::string command = "addr2line -f -C -e /proc/" + std::to_string(getpid()) + "/exe";
    for (size_t i = first; i < last; ++i) {
      char hex[32];
      // The return address is after the call; -1 lands inside the calling line.
      std::snprintf(hex, sizeof hex, " 0x%zx",
                    size_t(static_cast<char*>(in_exe[i]) - static_cast<char*>(self.dli_fbase)) - 1);
      command += hex;
    }
    std::FILE* pipe = popen(command.c_str(), "r");
    char line[4096];
    for (size_t i = first; i < last; ++i) {
      std::string function = "?", where = "?";
      if (pipe && std::fgets(line, sizeof line, pipe)) function = line;
      if (pipe && std::fgets(line, sizeof line, pipe)) where = line;
      for (std::string* s : {&function, &where})
        while (!s->empty() && (s->back() == '\n' || s->back() == '\r')) s->pop_back();
      where = where.substr(where.rfind('/') == std::string::npos ? 0 : where.rfind('/') + 1);
      names[in_exe[i]] = without_parameters(function) + " (" + where + ")";
    }
    if (pipe) pclose(pipe);
  }
  return names;
}

// Frames that say nothing about who allocated: the allocation functions themselves, this file,
// and library templates (containers, strings, iostreams, std::function).
bool is_plumbing(const std::string& name) {
  for (const char* prefix : {"operator new", "(anonymous namespace)::allocate",
                             "(anonymous namespace)::note_allocation", "std::", "void std::",
                             "__gnu_cxx::", "void __gnu_cxx::", "?"})
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

namespace rp::test {

bool AllocationCounter::enabled() { return RP_ALLOC_COUNTER != 0; }

uint64_t AllocationCounter::count() { return g_count.load(std::memory_order_relaxed); }

void AllocationCounter::start_recording() {
  void* warm[4];
  backtrace(warm, 4);  // the first call loads libgcc's unwinder (malloc, not recorded)
  g_traces_used.store(0);
  g_recording.store(true);
}

void AllocationCounter::stop_recording() { g_recording.store(false); }

std::string AllocationCounter::report(double per) {
  const bool was_recording = g_recording.exchange(false);
  const size_t n = std::min(g_traces_used.load(), kMaxTraces);
  std::vector<void*> addresses;
  for (size_t i = 0; i < n; ++i)
    addresses.insert(addresses.end(), g_traces[i].frames, g_traces[i].frames + g_traces[i].depth);
  std::sort(addresses.begin(), addresses.end());
  addresses.erase(std::unique(addresses.begin(), addresses.end()), addresses.end());
  const std::map<void*, std::string> names = symbolize(addresses);

  // Per allocation: its first frame outside the plumbing (the site) and the chain below it.
  std::map<std::string, size_t> by_site;
  std::map<std::string, size_t> by_chain;
  for (size_t i = 0; i < n; ++i) {
    std::vector<std::string> frames;
    for (int f = 0; f < g_traces[i].depth; ++f) frames.push_back(names.at(g_traces[i].frames[f]));
    size_t start = 0;  // after the last allocation function
    for (size_t f = 0; f < frames.size(); ++f)
      if (frames[f].rfind("operator new", 0) == 0) start = f + 1;
    size_t site = start;
    while (site < frames.size() && is_plumbing(frames[site])) ++site;
    std::string chain;
    for (size_t f = start; f < std::min(frames.size(), site + 3); ++f)
      chain += (chain.empty() ? "" : "\n      <- ") + frames[f];
    by_site[site < frames.size() ? frames[site] : "(no frame outside the library)"]++;
    by_chain[chain]++;
  }
  auto sorted = [](const std::map<std::string, size_t>& m) {
    std::vector<std::pair<std::string, size_t>> v(m.begin(), m.end());
    std::stable_sort(v.begin(), v.end(), [](auto& a, auto& b) { return a.second > b.second; });
    return v;
  };
  std::string out;
  char number[64];
  std::snprintf(number, sizeof number, "%zu allocations recorded", n);
  out += number;
  if (g_traces_used.load() > kMaxTraces) out += " (more happened; only the first are kept)";
  out += "\nby site (first frame outside the allocation and std:: templates), per unit:\n";
  for (const auto& [site, count] : sorted(by_site)) {
    std::snprintf(number, sizeof number, "  %7.2f  ", double(count) / per);
    out += number + site + "\n";
  }
  out += "by call chain:\n";
  for (const auto& [chain, count] : sorted(by_chain)) {
    std::snprintf(number, sizeof number, "  %7.2f  ", double(count) / per);
    out += number + chain + "\n";
  }
  if (was_recording) g_recording.store(true);
  return out;
}

}  // namespace rp::test

#if RP_ALLOC_COUNTER
void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t n, std::align_val_t a) { return allocate_aligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocate_aligned(n, a); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  try {
    return allocate_aligned(n, a);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  try {
    return allocate_aligned(n, a);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
#endif
