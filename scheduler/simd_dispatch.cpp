#include "scheduler/simd_dispatch.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace snee {
namespace {

// Where modules are looked for: beside the running program, in the lib/snee/ of the prefix it
// is installed under, and in the build tree that made it (tests and apps run from there).
std::vector<std::filesystem::path> module_directories() {
  std::vector<std::filesystem::path> dirs;
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    dirs.push_back(program.parent_path());
    dirs.push_back(program.parent_path().parent_path() / "lib" / "snee");
  }
  dirs.emplace_back(SNEE_SIMD_MODULE_DIR);
  return dirs;
}

}  // namespace

SimdModule load_simd_module(SimdLevel level,
                            const std::vector<std::filesystem::path>& directories) {
  SimdModule module;
  SimdLevelStatus& status = module.status;
  status.level = level;
  const std::string file = "snee-simd-" + std::string(simd_level_name(level)) + ".so";
  std::string looked;
  for (const std::filesystem::path& dir : directories) {
    const std::filesystem::path path = dir / file;
    looked += (looked.empty() ? "" : ", ") + dir.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) continue;
    // Never unloaded: its code may run until the process ends. RTLD_LOCAL keeps its symbols
    // from ever resolving another object's references.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      status.detail = "module " + path.string() + " does not load: " + dlerror();
      return module;
    }
    using Entry = const SimdBackend* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "snee_simd_backend"));
    const SimdBackend* backend = entry ? entry() : nullptr;
    if (!backend || backend->interface != kSimdBackendInterface ||
        backend->layout != simd_backend_layout() || backend->level != level ||
        std::string(backend->version) != SNEE_VERSION || !backend->render) {
      status.detail = "module " + path.string() +
                      " is from another build of snee (its interface, version or type layout "
                      "differs from this program's); rebuild it with this one";
      return module;
    }
    module.backend = backend;
    status.usable = true;
    status.detail = "module " + path.string();
    return module;
  }
  status.detail = "not built: no " + file + " in " + looked;
  return module;
}

namespace {

// Every level's standing and backend (null where unusable), by level, found once.
const std::vector<SimdModule>& levels() {
  static const std::vector<SimdModule> by_level = [] {
    std::vector<SimdModule> found;
    for (const SimdLevel level : kSimdLevels) {
      SimdModule m{{level, false, ""}, nullptr};
      if (!cpu_runs(level)) {
        m.status.detail = "this CPU lacks it";
      } else if (level == kCompiledSimdLevel) {
        m.status.usable = true;
        m.status.detail = "built in";
        m.backend = &compiled_backend();
      } else if (!SNEE_SIMD_DISPATCH) {
        m.status.detail = "not built (this build has SIMD dispatch off: -DSNEE_SIMD_DISPATCH=OFF)";
      } else if (!simd_module_built(level)) {
        m.status.detail = "not built (this build's -DSNEE_SIMD_MODULES leaves it out)";
      } else {
        m = load_simd_module(level, module_directories());
      }
      found.push_back(m);
    }
    return found;
  }();
  return by_level;
}

}  // namespace

const std::vector<SimdLevelStatus>& simd_levels() {
  static const std::vector<SimdLevelStatus> statuses = [] {
    std::vector<SimdLevelStatus> s;
    for (const SimdModule& m : levels()) s.push_back(m.status);
    return s;
  }();
  return statuses;
}

bool simd_module_built(SimdLevel level) {
  return (level == SimdLevel::kAvx2 && SNEE_SIMD_MODULE_AVX2) ||
         (level == SimdLevel::kAvx512 && SNEE_SIMD_MODULE_AVX512);
}

SimdLevel widest_simd_level() {
  SimdLevel widest = kCompiledSimdLevel;
  for (const SimdLevelStatus& s : simd_levels())
    if (s.usable) widest = s.level;
  return widest;
}

SimdLevel default_simd_level(const std::string& schedule) {
  return schedule == "megakernel" ? kCompiledSimdLevel : widest_simd_level();
}

const SimdBackend& simd_backend(SimdLevel level) {
  const SimdLevelStatus& status = simd_levels()[static_cast<size_t>(level)];
  if (!status.usable) {
    std::string usable;
    for (const SimdLevelStatus& s : simd_levels())
      if (s.usable) usable += (usable.empty() ? "" : ", ") + std::string(simd_level_name(s.level));
    throw std::invalid_argument("SIMD level " + std::string(simd_level_name(level)) +
                                " cannot be used here (" + status.detail + "); usable: " + usable);
  }
  return *levels()[static_cast<size_t>(level)].backend;
}

std::string simd_level_description(SimdLevel level) {
  return std::string(simd_level_name(level)) + " (" + std::to_string(simd_level_lanes(level)) +
         " float lanes)";
}

RenderResult render(const Scene& scene, const RenderOptions& options, const RenderHooks& hooks,
                    const FilmState* resume) {
  const SimdLevel level = options.simd.value_or(default_simd_level(options.schedule));
  return simd_backend(level).render(scene, options, hooks, resume);
}

}  // namespace snee
