// SPH throughput benchmark: particle-steps per second and neighbour
// interactions per second for snow and water at ~100k particles, on 1 and 2
// threads (a plain driver that prints figures; never a timed test).
//   build/bin/sph_bench [--particles N] [--steps S]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <omp.h>
#include <string>

#include "cosim/error.hpp"
#include "cosim/scene_io.hpp"
#include "snow_sph/scene.hpp"
#include "snow_sph/solver.hpp"

namespace {

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

void run(bool snow, long n, int steps, int threads, const std::string& materials) {
  omp_set_num_threads(threads);
  snow_sph::Model model = snow_sph::build_model(make_scene(snow, n, materials));
  snow_sph::Solver solver(model);
  solver.initialise();
  for (int i = 0; i < 5; ++i) solver.step();  // warm-up (first list build, caches)
  const auto interactions0 = solver.interactions();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) solver.step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double pairs = static_cast<double>(solver.interactions() - interactions0);
  const double particles = static_cast<double>(model.particles.n_real);
  // Interactions: pairs within the support per step, counted from both sides
  // (as DualSPHysics counts them), although each is visited twice a step.
  std::printf("%-6s %8.0f particles  %d thread(s)  %4d steps  %7.2f s  %9.0f particle-steps/s  "
              "%5.1f neighbours  %6.1f M interactions/s  rebuilds %zu\n",
              snow ? "snow" : "water", particles, threads, steps, wall, particles * steps / wall,
              pairs / (particles * steps), pairs / wall / 1e6, solver.rebuilds());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  long n = 100000;
  int steps = 50;
  std::string materials = "configs/materials";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--particles")) n = std::atol(argv[i + 1]);
    if (!std::strcmp(argv[i], "--steps")) steps = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--materials")) materials = argv[i + 1];
  }
  std::printf("SPH benchmark: cubic kernel, h = 1.2 dx, double precision, %d hardware threads\n",
              omp_get_num_procs());
  try {
    for (bool snow : {true, false})
      for (int threads : {1, 2}) run(snow, n, steps, threads, materials);
  } catch (const cosim::Error& e) {
    std::fprintf(stderr, "sph_bench: %s (run it from the repository root or pass --materials DIR)\n",
                 e.what());
    return 1;
  }
  return 0;
}
