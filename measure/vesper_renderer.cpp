#include "measure/vesper_renderer.h"

#include <elf.h>
#include <link.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "renderer/render/render.h"
#include "renderer/scene/scene.h"
#include "renderer/scene/scene_loader.h"

namespace vesper::measure {
namespace {

// The main program's NT_GNU_BUILD_ID note, as hex; "" when it has none.
std::string main_build_id() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) -> int {
        // The first object listed is the main program.
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const ElfW(Phdr)& ph = info->dlpi_phdr[i];
          if (ph.p_type != PT_NOTE) continue;
          const char* p = reinterpret_cast<const char*>(info->dlpi_addr + ph.p_vaddr);
          const char* end = p + ph.p_memsz;
          while (p + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
            const char* name = p + sizeof(ElfW(Nhdr));
            const char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 &&
                std::string_view(name, 3) == "GNU") {
              auto* hex = static_cast<std::string*>(out);
              for (unsigned k = 0; k < note->n_descsz; ++k)
                *hex += fmt::format("{:02x}", static_cast<unsigned char>(desc[k]));
              return 1;
            }
            p = desc + ((note->n_descsz + 3) & ~3u);
          }
        }
        return 1;
      },
      &id);
  return id;
}

std::string executable_stamp() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "unknown";
  const auto size = std::filesystem::file_size(exe, ec);
  const auto mtime = std::filesystem::last_write_time(exe, ec);
  if (ec) return "unknown";
  return fmt::format("size {} mtime {}", size, mtime.time_since_epoch().count());
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

RenderedImage render_scene(const BenchScene& bench, int spp, uint64_t seed, int threads,
                           const VesperRendererOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  SceneDescription desc = load_scene(bench.scene_path);
  desc.film.width = bench.width;
  desc.film.height = bench.height;
  // A fixed spp: the ladder, not the scene's noise target or time budget, decides.
  desc.render.noise_target.reset();
  desc.render.min_spp.reset();
  desc.render.max_spp.reset();
  desc.render.time_limit.reset();
  const Scene scene = build_scene(desc);
  RenderOptions ro;
  ro.threads = threads;
  ro.spp = spp;
  ro.seed = seed;
  ro.aovs = std::vector<Aov>{};
  ro.on_progress = options.on_progress;
  RenderResult result = render(scene, ro);
  RenderedImage out;
  out.image = std::move(result.image);
  out.render_seconds = result.stats.seconds;
  out.wall_seconds = seconds_since(t0);
  return out;
}

}  // namespace

std::string vesper_cache_key() {
  const std::string id = main_build_id();
  return fmt::format("vesper {} build {}", VESPER_VERSION, id.empty() ? executable_stamp() : id);
}

BenchRenderer vesper_renderer(const VesperRendererOptions& options) {
  BenchRenderer r;
  r.name = "vesper";
  r.cache_key = vesper_cache_key();
  r.render = [options](const BenchScene& scene, int spp, uint64_t seed, int threads) {
    try {
      return render_scene(scene, spp, seed, threads, options);
    } catch (const std::exception& e) {
      throw std::runtime_error(fmt::format("vesper: {}: {}", scene.name, e.what()));
    }
  };
  return r;
}

}  // namespace vesper::measure
