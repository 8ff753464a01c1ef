// The peer block of ../shared/notes/peers.md ("Explicit FE: CalculiX 2.20") in
// tyre_fe: a 0.2 x 0.2 x 0.05 m block of one-point hexahedra, the tread's Yeoh rubber
// (K0 = 20 mu0), bottom fixed, top pushed down at 0.5 m/s, stepped with the tyre's own
// step3d (element kernel, material law, gather, central difference) at the model's
// stable step. Prints us per element-step on 1 and 2 threads (wall time: median of the
// repeats and the spread; CPU time of all threads: median), the share of the element
// kernels + gather in the step and the peak memory.
//   block_bench [--divisions NX NY NZ] [--steps N | --end-time S] [--repeats R] [--threads 1 2]
// bench/calculix_bench.sh runs it beside CalculiX's ccx on the same block.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <omp.h>
#include <sys/resource.h>

#include "cosim/error.hpp"
#include "tyre_fe/model3d.hpp"
#include "tyre_fe/solver3d.hpp"

namespace {

using namespace tyre_fe;
constexpr double kSize[3] = {0.2, 0.2, 0.05};  // block edges x, y, z [m]
constexpr double kPushSpeed = 0.5;              // top moves down [m/s]

// Node (i, j, k) of an (nx+1) x (ny+1) x (nz+1) grid.
int node_id(int i, int j, int k, const int n[3]) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); }

// The block as a tread-only Mesh3D. The bottom nodes are rim nodes: step3d moves them
// with the rigid rim, which the driver holds, so they stay fixed (as the tied bead).
Mesh3D block_mesh(const int n[3]) {
  Mesh3D m;
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        m.nodes.emplace_back(kSize[0] * i / n[0], kSize[1] * j / n[1], kSize[2] * k / n[2]);
        m.node_source.push_back(-1), m.node_angle_rad.push_back(0.0);
        if (k == 0) m.rim_nodes.push_back(node_id(i, j, k, n));
      }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        m.hexes.push_back({node_id(i, j, k, n), node_id(i + 1, j, k, n), node_id(i + 1, j + 1, k, n),
                           node_id(i, j + 1, k, n), node_id(i, j, k + 1, n), node_id(i + 1, j, k + 1, n),
                           node_id(i + 1, j + 1, k + 1, n), node_id(i, j + 1, k + 1, n)});
        m.hex_region.push_back(Region::tread), m.hex_source_quad.push_back(-1), m.hex_angle_rad.push_back(0.0);
      }
  return m;
}

// Thesis tread (configs/materials/tyre_235_75R15.textproto), K0 = 20 mu0; no rebar.
TyreMaterials tread_materials() {
  TyreMaterials mats;
  for (SolidMaterial& s : mats.solid) {
    s.kind = SolidMaterial::Kind::yeoh;
    s.yeoh.C10_Pa = 777561.0, s.yeoh.C20_Pa = -276138.0, s.yeoh.C30_Pa = 95427.0;
    s.yeoh.density_kg_per_m3 = 1178.0;
    s.yeoh.bulk_modulus_Pa = 20.0 * s.yeoh.initial_shear_modulus_Pa();
  }
  return mats;
}

struct Run {
  double wall_s = 0.0, cpu_s = 0.0, internal_share = 0.0, top_force_N = 0.0;
};

// User + system CPU time of the process (all threads) [s].
double cpu_time_s() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// N steps from the reference state; after each step the top nodes are put back on
// their prescribed path (x, y held, z = z0 - v t, velocity -v). The top reaction is
// that of the last step's internal forces.
Run run(const Model3d& model, const State3d& start, const std::vector<int>& top, int steps) {
  State3d s = start;
  RimDrive held;  // x, spin held (defaults) and z held: the bottom stays where it is
  held.hold_z = true;
  const double t0 = omp_get_wtime(), c0 = cpu_time_s();
  for (int k = 0; k < steps; ++k) {
    if (!step3d(model, s, held)) throw cosim::Error("block_bench: non-finite state at step " + std::to_string(k));
    for (int i : top) {
      const Eigen::Vector3d& X = model.mesh.nodes[i];
      s.x[i] = X.x(), s.y[i] = X.y(), s.z[i] = X.z() - kPushSpeed * s.time_s;
      s.vx[i] = s.vy[i] = 0.0, s.vz[i] = -kPushSpeed;
    }
  }
  Run r;
  r.wall_s = omp_get_wtime() - t0;
  r.cpu_s = cpu_time_s() - c0;
  const auto& st = s.stage_times;
  r.internal_share = st.internal_forces_s / (st.internal_forces_s + st.contact_s + st.rest_s);
  for (int i : top) r.top_force_N -= s.fz[i];  // reaction on the top (z), as ccx's RF
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"block_bench: tyre_fe's explicit step on the CalculiX peer block"};
  std::vector<int> div{44, 44, 11}, thread_counts{1, 2};
  int steps = 400, repeats = 3;
  double end_time_s = 0.0;
  app.add_option("--divisions", div, "elements along x, y, z")->expected(3);
  app.add_option("--steps", steps, "steps per run (from the reference state)")->check(CLI::PositiveNumber);
  app.add_option("--end-time", end_time_s, "run to the step nearest this time [s] (instead of --steps)")
      ->check(CLI::PositiveNumber);
  app.add_option("--repeats", repeats, "runs per thread count (median reported)")->check(CLI::PositiveNumber);
  app.add_option("--threads", thread_counts, "thread counts to time")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  try {
    const int n[3] = {div[0], div[1], div[2]};
    if (n[0] < 1 || n[1] < 1 || n[2] < 1) throw cosim::Error("--divisions: each must be >= 1");
    const Model3d model = build_model3d(block_mesh(n), tread_materials(), CrossSection{}, Model3dOptions{});
    if (end_time_s > 0.0) steps = std::max(1, static_cast<int>(std::lround(end_time_s / model.stable_dt_s)));
    std::vector<Eigen::Vector3d> x = model.mesh.nodes;
    State3d start = make_state3d(model, x, 0.0, 0.0);
    start.time_stages = true;
    std::vector<int> top;
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) top.push_back(node_id(i, j, n[2], n));
    const std::size_t ne = model.mesh.hexes.size();
    const double h = kSize[2] / n[2], c = model.element_wave_speed[0];
    std::printf("block_bench: %d x %d x %d = %zu hexahedra, %zu nodes, c %.1f m/s, dt %.4g s (%.3f h/c), %d steps,"
                " end time %.4g s\n", n[0], n[1], n[2], ne, x.size(), c, model.stable_dt_s,
                model.stable_dt_s * c / h, steps, steps * model.stable_dt_s);
    for (int threads : thread_counts) {
      omp_set_num_threads(threads);
      std::vector<Run> runs;
      for (int r = 0; r < repeats; ++r) runs.push_back(run(model, start, top, steps));
      std::vector<double> us, cpu_us;
      for (const Run& r : runs) us.push_back(1e6 * r.wall_s / (double(steps) * ne));
      for (const Run& r : runs) cpu_us.push_back(1e6 * r.cpu_s / (double(steps) * ne));
      std::sort(us.begin(), us.end());
      std::sort(cpu_us.begin(), cpu_us.end());
      // RESULT lines are read by bench/calculix_bench.sh.
      std::printf("RESULT threads %d us_per_element_step %.4f min %.4f max %.4f dt_s %.6g internal_share %.3f"
                  " top_force_N %.2f cpu_us_per_element_step %.4f\n", threads, us[us.size() / 2], us.front(),
                  us.back(), model.stable_dt_s, runs.back().internal_share, runs.back().top_force_N,
                  cpu_us[cpu_us.size() / 2]);
    }
    rusage usage{};  // peak memory
    getrusage(RUSAGE_SELF, &usage);
    std::printf("PEAK_RSS_MB %.1f\n", usage.ru_maxrss / 1024.0);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "block_bench: error: %s\n", e.what());
    return 2;
  }
}
