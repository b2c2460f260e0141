// The run's plot, drawn by gnuplot through gnuplot-iostream (the only file that includes it, with
// its Boost.Iostreams machinery).

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include <gnuplot-iostream.h>

#include "outputs.h"

namespace rbsim {
namespace {

std::string Quoted(const std::string& s) {  // a gnuplot single-quoted string
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string ShellQuoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool HaveGnuplot() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

void WritePlot(const std::string& path, const Simulation& sim, const Recording& rec) {
  namespace fs = std::filesystem;
  const bool png = fs::path(path).extension() == ".png";
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  const std::string log = path + ".log-" + std::to_string(::getpid());
  // At most ~20000 points per curve: beyond that a plot shows nothing more.
  const std::size_t n = rec.times.size();
  const std::size_t stride = std::max<std::size_t>(1, n / 20000);
  std::vector<std::tuple<double, double, double, double>> omega;
  std::vector<std::pair<double, double>> energy, momentum;
  for (std::size_t i = 0; i < n; i += stride) {
    const Vector3& w = rec.omega_principal[i];
    omega.emplace_back(rec.times[i], w.x(), w.y(), w.z());
    energy.emplace_back(rec.times[i], rec.energy_drift[i]);
    momentum.emplace_back(rec.times[i], rec.momentum_drift[i]);
  }
  const SimBody& body = sim.bodies[static_cast<std::size_t>(sim.scene.plot_body)];
  const std::string title =
      fs::path(sim.scene.file).filename().string() + ": " + body.name + ", " +
      dynamics::IntegratorName(sim.scene.integrator) +
      ", dt = " + std::to_string(sim.scene.dt).erase(std::to_string(sim.scene.dt).find_last_not_of('0') + 1) + " s";
  {
    Gnuplot gp("gnuplot 2>" + ShellQuoted(log));
    gp << (png ? "set terminal pngcairo noenhanced size 1000,900 font 'sans,11'\n"
               : "set terminal svg noenhanced size 1000,900 dynamic font 'sans,11' background rgb 'white'\n");
    gp << "set output " << Quoted(tmp) << "\n";
    gp << "set multiplot layout 3,1 title " << Quoted(title) << "\n";
    gp << "set grid\nset key outside right\nset lmargin 14\nset rmargin 18\n";
    gp << "set xrange [" << rec.times.front() << ":" << rec.times.back() << "]\n";
    gp << "set ylabel 'rad/s'\nset title 'angular velocity in the principal axes (I1 <= I2 <= I3)'\n";
    gp << "plot '-' using 1:2 with lines lw 1.5 title 'w1', '' using 1:3 with lines lw 1.5 title 'w2', "
          "'' using 1:4 with lines lw 1.5 title 'w3'\n";
    gp.send1d(omega);
    gp.send1d(omega);
    gp.send1d(omega);
    gp << "set format y '%.1e'\nset ylabel 'relative'\n";
    gp << "set title "
       << Quoted(sim.conservation.energy
                     ? "energy drift (E - E0)/|E0|  (conserved by the physics)"
                     : "energy change (E - E0)/|E0|  (not conserved: " + sim.conservation.energy_broken_by + ")")
       << "\n";
    gp << "plot '-' with lines lw 1.5 lc rgb '#d55e00' title 'energy'\n";
    gp.send1d(energy);
    gp << "set xlabel 'time, s'\n";
    gp << "set title "
       << Quoted(sim.conservation.momentum ? "angular momentum drift (|L| - |L0|)/|L0|, about the world origin"
                                           : "angular momentum change (|L| - |L0|)/|L0|  (not conserved: " +
                                                 sim.conservation.momentum_broken_by + ")")
       << "\n";
    gp << "plot '-' with lines lw 1.5 lc rgb '#0072b2' title '|L|'\n";
    gp.send1d(momentum);
    gp << "unset multiplot\nset output\nexit\n";
  }  // waits for gnuplot to finish
  std::error_code ec;
  const bool made = fs::is_regular_file(tmp, ec) && fs::file_size(tmp, ec) > 0;
  std::string messages;
  {
    std::ifstream in(log);
    std::getline(in, messages, '\0');
  }
  fs::remove(log, ec);
  if (!made) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path + ": gnuplot did not draw the plot" + (messages.empty() ? "" : ": " + messages));
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path + ": cannot rename the finished plot into place");
  }
}

}  // namespace rbsim
