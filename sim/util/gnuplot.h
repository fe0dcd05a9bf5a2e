#pragma once
// Renders PNG figures with gnuplot (Debian's gnuplot-nox, pngcairo terminal).
// Data travels inside the script as inline data blocks ($name << EOD), so a
// figure is one self-contained script; the PNG is written to a temporary file
// and renamed into place, so a failed plot never leaves half an image.
//
//   GnuplotFigure fig("out.png", 1400, 900);
//   fig.data("temps", {"t_h", "chamber"}, {t, chamber});
//   fig.commands("plot $temps using 1:2 with lines title 'chamber'");
//   fig.render();

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace gyrotherm {

class GnuplotFigure {
 public:
  GnuplotFigure(std::filesystem::path png, int width_px = 1400, int height_px = 900);

  // An inline data block $name with equally long columns (NaN becomes a
  // gap). A blank line goes before each row in `breaks` (increasing): lines
  // and line-points do not join across it, for gaps in a record.
  void data(const std::string& name, const std::vector<std::string>& column_names,
            const std::vector<std::span<const double>>& columns, std::span<const std::size_t> breaks = {});
  // Plot commands appended to the script (after the terminal set-up).
  void commands(const std::string& text);
  // Runs gnuplot; throws InputError naming the PNG if gnuplot is missing or fails.
  void render() const;

 private:
  std::filesystem::path png_;
  int width_px_;
  int height_px_;
  std::string data_;
  std::string commands_;
};

// Averages of consecutive windows of `window` samples (the last partial window
// is dropped); used to plot 100 s averages of 1 Hz data.
std::vector<double> window_means(std::span<const double> values, std::size_t window);

}  // namespace gyrotherm
