#include "sim/util/gnuplot.h"

#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <system_error>

#include "sim/util/atomic_file.h"
#include "sim/util/input_error.h"

namespace gyrotherm {

GnuplotFigure::GnuplotFigure(std::filesystem::path png, int width_px, int height_px)
    : png_(std::move(png)), width_px_(width_px), height_px_(height_px) {}

void GnuplotFigure::data(const std::string& name, const std::vector<std::string>& column_names,
                         const std::vector<std::span<const double>>& columns,
                         std::span<const std::size_t> breaks) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "${} << EOD\n#", name);
  for (const std::string& c : column_names) fmt::format_to(std::back_inserter(out), " {}", c);
  out.push_back('\n');
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  std::size_t next_break = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (next_break < breaks.size() && breaks[next_break] == r) {
      out.push_back('\n');
      ++next_break;
    }
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double v = columns[c][r];
      if (c > 0) out.push_back(' ');
      if (std::isfinite(v))
        fmt::format_to(std::back_inserter(out), "{:.9g}", v);
      else
        fmt::format_to(std::back_inserter(out), "NaN");
    }
    out.push_back('\n');
  }
  fmt::format_to(std::back_inserter(out), "EOD\n");
  data_ += fmt::to_string(out);
}

void GnuplotFigure::commands(const std::string& text) {
  commands_ += text;
  if (!text.empty() && text.back() != '\n') commands_ += '\n';
}

void GnuplotFigure::render() const {
  std::filesystem::path temporary_path = png_;
  temporary_path += ".tmp." + std::to_string(::getpid());
  TemporaryPath guard(temporary_path);  // removed on failure or interruption
  const std::filesystem::path& temporary = guard.path();
  std::filesystem::path script = png_;
  script += ".gp.tmp." + std::to_string(::getpid());
  const std::string text =
      fmt::format("set terminal pngcairo size {},{} font 'DejaVu Sans,11' noenhanced\n"
                  "set output '{}'\nset datafile missing 'NaN'\nset grid\n",
                  width_px_, height_px_, temporary.string()) +
      data_ + commands_ + "unset output\n";
  write_file_atomically(script, text);
  const std::string command = "gnuplot '" + script.string() + "' 2> '" + script.string() + ".err'";
  const int status = std::system(command.c_str());
  std::error_code ignored;
  std::string error_text;
  {
    std::FILE* f = std::fopen((script.string() + ".err").c_str(), "r");
    if (f != nullptr) {
      char buffer[512];
      std::size_t n = 0;
      while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) error_text.append(buffer, n);
      std::fclose(f);
    }
  }
  std::filesystem::remove(script, ignored);
  std::filesystem::remove(script.string() + ".err", ignored);
  const bool ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0 &&
                  std::filesystem::exists(temporary);
  if (!ok) {
    std::filesystem::remove(temporary, ignored);
    const bool missing = WIFEXITED(status) && WEXITSTATUS(status) == 127;
    throw InputError(png_.string() + ": " +
                     (missing ? std::string("gnuplot is not installed (scripts/setup.sh installs "
                                            "gnuplot-nox)")
                              : "gnuplot failed: " + error_text));
  }
  std::filesystem::rename(temporary, png_);
  guard.release();
}

std::vector<double> window_means(std::span<const double> values, std::size_t window) {
  std::vector<double> out;
  if (window == 0) return out;
  for (std::size_t start = 0; start + window <= values.size(); start += window) {
    double sum = 0.0;
    for (std::size_t k = start; k < start + window; ++k) sum += values[k];
    out.push_back(sum / static_cast<double>(window));
  }
  return out;
}

}  // namespace gyrotherm
