// SPH throughput benchmark: particle-steps per second and neighbour
// interactions per second for snow and water at ~100k particles, on 1 and 2
// threads (a plain driver that prints figures; never a timed test).
//   build/bin/sph_bench [--particles N] [--steps S] [--repeats R]
// Each case runs R times (default 5) from a fresh model and prints the median and
// the range; the header prints the load average, since another process on a
// 2-core machine takes a core from the 2-thread runs (docs/performance.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <omp.h>
#include <string>
#include <vector>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"

namespace {

// The 1-minute load average (/proc/loadavg): other work on the machine.
std::string load_average() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  char buffer[64] = "unknown";
  if (f) {
    if (!std::fgets(buffer, sizeof buffer, f)) std::strcpy(buffer, "unknown");
    std::fclose(f);
  }
  std::string text(buffer);
  return text.substr(0, text.find(' '));
}

// A cube of `n` particles at 10 mm: snow (soft, geostatic, with gravity) or
// water (hydrostatic, physical sound speed 1500 m/s).
cosim::scene::Scene make_scene(bool snow, long n, const std::string& materials) {
  const double dx = 0.01;
  const long side = static_cast<long>(std::cbrt(static_cast<double>(n)) + 0.5);
  cosim::scene::Scene s;
  s.set_name(snow ? "bench_snow" : "bench_water");
  s.mutable_time()->set_end_time_s(1.0);
  s.mutable_time()->set_cfl(0.3);
  auto* sph = s.mutable_sph();
  sph->set_kernel(cosim::scene::CUBIC);
  sph->set_particle_spacing_m(dx);
  sph->set_smoothing_length_ratio(1.2);
  sph->mutable_gravity_m_per_s2()->set_z(-9.81);
  const double L = side * dx;
  auto* box = sph->mutable_container();
  box->mutable_max()->set_x(L), box->mutable_max()->set_y(L), box->mutable_max()->set_z(1.5 * L);
  auto* block = sph->add_blocks();
  block->mutable_region()->mutable_max()->set_x(L);
  block->mutable_region()->mutable_max()->set_y(L);
  block->mutable_region()->mutable_max()->set_z(L);
  block->set_geostatic_initial_state(true);
  cosim::scene::Material m;
  google::protobuf::TextFormat::ParseFromString(
      cosim::read_file(materials + (snow ? "/snow_soft.textproto" : "/water.textproto")), &m);
  *block->mutable_material() = m;
  sph->mutable_artificial_viscosity()->set_alpha(snow ? 1.0 : 0.05);
  sph->mutable_artificial_viscosity()->set_beta(snow ? 1.0 : 0.0);
  if (!snow) sph->set_density_diffusion_delta(0.1);
  return s;
}

struct Figures {
  double wall_s = 0.0, particle_steps_per_s = 0.0, interactions_per_s = 0.0, neighbours = 0.0, particles = 0.0;
  std::size_t rebuilds = 0;
};

// One timed run: a fresh model, 5 warm-up steps (first list build, caches), then `steps` steps.
Figures run(bool snow, long n, int steps, int threads, const std::string& materials) {
  omp_set_num_threads(threads);
  snow_sph::Model model = snow_sph::build_model(make_scene(snow, n, materials));
  snow_sph::Solver solver(model);
  solver.initialise();
  for (int i = 0; i < 5; ++i) solver.step();
  const auto interactions0 = solver.interactions();
  const auto rebuilds0 = solver.rebuilds();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) solver.step();
  Figures f;
  f.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double pairs = static_cast<double>(solver.interactions() - interactions0);
  f.particles = static_cast<double>(model.particles.n_real);
  f.particle_steps_per_s = f.particles * steps / f.wall_s;
  f.interactions_per_s = pairs / f.wall_s;
  f.neighbours = pairs / (f.particles * steps);
  f.rebuilds = solver.rebuilds() - rebuilds0;
  return f;
}

// Median, smallest and largest of `repeats` runs, so that a quoted figure comes
// with the spread a user will see on a shared machine.
void report(bool snow, long n, int steps, int threads, int repeats, const std::string& materials) {
  std::vector<Figures> runs;
  for (int r = 0; r < repeats; ++r) runs.push_back(run(snow, n, steps, threads, materials));
  std::vector<double> rate;
  for (const auto& f : runs) rate.push_back(f.interactions_per_s / 1e6);
  std::sort(rate.begin(), rate.end());
  const double median = rate.size() % 2 ? rate[rate.size() / 2] : 0.5 * (rate[rate.size() / 2 - 1] + rate[rate.size() / 2]);
  std::size_t rebuilds = 0;
  for (const auto& f : runs) rebuilds += f.rebuilds;
  // Interactions: pairs within the support per step, counted from both sides
  // (as DualSPHysics counts them), although each is visited twice a step.
  std::printf("%-6s %8.0f particles  %d thread(s)  %4d steps x %d runs  %5.1f neighbours  "
              "M interactions/s: median %6.1f  range %6.1f - %6.1f  (%9.0f particle-steps/s median)  "
              "list rebuilds in the timed steps %zu\n",
              snow ? "snow" : "water", runs[0].particles, threads, steps, repeats, runs[0].neighbours, median,
              rate.front(), rate.back(), median * 1e6 / runs[0].neighbours, rebuilds);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  long n = 100000;
  int steps = 50;
  int repeats = 5;
  std::string materials = "configs/materials";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--particles")) n = std::atol(argv[i + 1]);
    if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--repeats")) repeats = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--materials")) materials = argv[i + 1];
  }
  const char* bind = std::getenv("OMP_PROC_BIND");
  std::printf("SPH benchmark: cubic kernel, h = 1.2 dx, double precision, %d hardware threads, OMP_PROC_BIND=%s, "
              "load average %s\n", omp_get_num_procs(), bind ? bind : "(unset)", load_average().c_str());
  try {
    for (bool snow : {true, false})
      for (int threads : {1, 2}) report(snow, n, steps, threads, repeats, materials);
  } catch (const cosim::Error& e) {
    std::fprintf(stderr, "sph_bench: %s (run it from the repository root or pass --materials DIR)\n",
                 e.what());
    return 1;
  }
  return 0;
}
