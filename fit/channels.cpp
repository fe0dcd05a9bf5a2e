#include "fit/channels.h"

#include <algorithm>
#include <cctype>

namespace gyrotherm::fit {

std::vector<std::string> parse_channels(const std::string& list) {
  std::vector<std::string> out;
  for (std::size_t from = 0;;) {
    const std::size_t comma = list.find(',', from);
    std::string name = list.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    const auto first = name.find_first_not_of(" \t"), last = name.find_last_not_of(" \t");
    name = first == std::string::npos ? std::string() : name.substr(first, last - first + 1);
    if (name.empty())
      throw InputError(fmt::format("--gyro-col {}: an empty channel name (expected NAME or NAME,NAME,...)", list));
    if (std::find(out.begin(), out.end(), name) != out.end())
      throw InputError(fmt::format("--gyro-col {}: channel '{}' is named twice", list, name));
    out.push_back(name);
    if (comma == std::string::npos) break;
    from = comma + 1;
  }
  return out;
}

namespace {

std::string file_safe(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || (c == '.' && !out.empty());
    if (keep) out += c;
    else if (out.empty() || out.back() != '_') out += '_';
  }
  while (out.size() > 1 && out.back() == '_') out.pop_back();
  return out.empty() || out == "_" ? "channel" : out;
}

}  // namespace

std::vector<std::string> channel_file_names(const std::vector<std::string>& channels) {
  std::vector<std::string> out;
  for (const std::string& channel : channels) {
    const std::string base = file_safe(channel);
    std::string name = base;
    for (int k = 2; std::find(out.begin(), out.end(), name) != out.end(); ++k) name = fmt::format("{}_{}", base, k);
    out.push_back(name);
  }
  return out;
}

PipelineOptions for_channel(PipelineOptions pipeline, const std::string& channel) {
  pipeline.columns.gyro = channel;
  return pipeline;
}

}  // namespace gyrotherm::fit
