// The definitions of batch.h: `massprops batch` and `massprops merge`.

#include "batch.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "massprops/io/isolation.h"
#include "massprops/io/mesh_io.h"
#include "massprops/parallel.h"
#include "massprops/report/atomic_file.h"
#include "massprops/report/format.h"
#include "massprops/report/record.h"

namespace massprops::cli {
using namespace massprops::report;  // the formats this command prints
namespace {

using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

int Bad(const std::string& what) {
  massprops::app::PrintError(what);
  return app::kBadArguments;
}

// The files of a folder (recursively, every extension a reader knows) or of a manifest (one path
// a line; blank lines and lines starting with # skipped), sorted by path.
std::vector<std::string> ListFiles(const std::string& input) {
  std::vector<std::string> files;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    for (auto it = fs::recursive_directory_iterator(input, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (it->is_regular_file(ec) && IsMeshFile(it->path().string())) files.push_back(it->path().string());
    }
    if (ec) throw std::runtime_error(input + ": cannot walk the folder (" + ec.message() + ")");
  } else {
    std::ifstream in(input);
    if (!in) throw std::runtime_error(input + ": cannot open the manifest");
    std::string line;
    while (std::getline(in, line)) {
      const auto b = line.find_first_not_of(" \t\r");
      if (b == std::string::npos || line[b] == '#') continue;
      const auto e = line.find_last_not_of(" \t\r");
      files.push_back(line.substr(b, e - b + 1));
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

// The complete records of a JSON Lines file (a torn last line, from an interrupted run, is not
// one); `complete_bytes` is where the last complete line ends. @throws for a line that is not a
// record in the middle of the file.
std::vector<Json> ReadRecords(const std::string& path, std::size_t& complete_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<Json> out;
  complete_bytes = 0;
  std::size_t line_no = 0;
  for (std::size_t at = 0; at < all.size();) {
    const std::size_t eol = all.find('\n', at);
    if (eol == std::string::npos) break;  // torn: no end of line
    ++line_no;
    Json j = Json::parse(all.begin() + static_cast<std::ptrdiff_t>(at), all.begin() + static_cast<std::ptrdiff_t>(eol),
                         nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("file") || !j.contains("status")) {
      throw std::runtime_error(path + ": line " + std::to_string(line_no) + " is not a batch record");
    }
    out.push_back(std::move(j));
    at = complete_bytes = eol + 1;
  }
  return out;
}

// Why the checks refused a mesh, from the message (for the summary).
std::string RefusalReason(const std::string& message) {
  const std::pair<const char*, const char*> reasons[] = {
      {"open mesh", "open"},
      {"inconsistent orientation", "inconsistent orientation"},
      {"faces point inward", "inward"},
      {"double-sided", "duplicate faces"},
      {"repeat the corners", "duplicate faces"},
      {"volumes overlap", "overlapping shells"},
      {"intersect:", "overlapping shells"},
      {"faces inward but", "inward shell"},
      {"volume is zero", "zero volume"},
      {"double precision", "size out of range"},
      {"thicker than the part", "wall too thick"},
  };
  for (const auto& [needle, reason] : reasons) {
    if (message.find(needle) != std::string::npos) return reason;
  }
  return "other";
}

struct Summary {
  std::size_t files = 0, skipped = 0, ok = 0, refused = 0, error = 0, crashed = 0, timeout = 0;
  std::size_t warned = 0;  // ok, with warnings
  std::map<std::string, std::size_t> refused_by_reason;
  double triangles = 0;

  void Add(const Json& rec) {
    const std::string status = rec.at("status");
    if (status == "ok") {
      ++ok;
      const Json& r = rec.at("result");
      if (r.contains("mesh") && r["mesh"].contains("triangles")) triangles += r["mesh"]["triangles"].get<double>();
      if (!r.at("warnings").empty()) ++warned;
    } else if (status == "refused") {
      ++refused;
      ++refused_by_reason[RefusalReason(rec.value("message", ""))];
    } else if (status == "error") {
      ++error;
    } else if (status == "crashed") {
      ++crashed;
    } else if (status == "timeout") {
      ++timeout;
    }
  }
  Json ToJson(double seconds) const {
    Json reasons = Json::object();
    for (const auto& [reason, n] : refused_by_reason) reasons[reason] = n;
    return {{"files", files},     {"skipped_as_done", skipped},   {"ok", ok},          {"ok_with_warnings", warned},
            {"refused", refused}, {"refused_by_reason", reasons}, {"error", error},    {"crashed", crashed},
            {"timeout", timeout}, {"triangles", triangles},       {"seconds", seconds}};
  }
  std::string ToText(double seconds) const {
    std::ostringstream s;
    const std::size_t computed = files - skipped;
    s << "batch: " << files << " files";
    if (skipped > 0) s << " (" << skipped << " done before, skipped)";
    s << ": " << ok << " solids";
    if (warned > 0) s << " (" << warned << " with warnings)";
    s << ", " << refused << " refused";
    if (!refused_by_reason.empty()) {
      s << " (";
      const char* sep = "";
      for (const auto& [reason, n] : refused_by_reason) {
        s << sep << n << " " << reason;
        sep = ", ";
      }
      s << ")";
    }
    s << ", " << error << " unreadable or malformed, " << crashed << " crashed, " << timeout << " timed out; ";
    s.precision(3);
    s << computed << " computed in " << seconds << " s (" << (seconds > 0 ? static_cast<double>(computed) / seconds : 0)
      << " files/s, " << (seconds > 0 ? triangles / seconds : 0) << " triangles/s)";
    return s.str();
  }
};

}  // namespace

void ParseShard(const std::string& text, int& index, int& count) {
  const std::size_t slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("");
    std::size_t used_i = 0, used_n = 0;
    index = std::stoi(text.substr(0, slash), &used_i);
    count = std::stoi(text.substr(slash + 1), &used_n);
    if (used_i != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw std::invalid_argument("--shard takes i/n (e.g. 3/16), not '" + text + "'");
  }
  if (count < 1 || index < 0 || index >= count) {
    throw std::invalid_argument("--shard " + text + ": needs 0 <= i < n");
  }
}

constexpr std::size_t kFilesPerProcess = 64;

int RunBatch(const BatchOptions& b) {
  std::error_code ec;
  if (!fs::exists(b.input, ec)) return Bad(b.input + ": no such folder or manifest");
  if (!fs::is_directory(b.input, ec) && IsMeshFile(b.input)) {
    return Bad(b.input + ": batch takes a folder or a manifest (a text file with one path a line), not a mesh file");
  }
  std::vector<std::string> all;
  try {
    all = ListFiles(b.input);
    report::CheckOutputPath(b.output, {b.input});
  } catch (const std::exception& e) {
    return Bad(e.what());
  }
  // This shard's files: those whose index in the sorted list is ≡ i (mod n).
  std::vector<std::size_t> mine;
  for (std::size_t i = static_cast<std::size_t>(b.shard_index); i < all.size();
       i += static_cast<std::size_t>(b.shard_count)) {
    mine.push_back(i);
  }
  Summary summary;
  summary.files = mine.size();
  // Resume: keep the complete records, drop a torn last line, skip the files already done.
  std::set<std::string> done;
  const bool exists = fs::exists(b.output, ec) && fs::file_size(b.output, ec) > 0;
  if (exists && !b.resume) {
    return Bad(b.output + " exists: --resume goes on from the records in it (or remove it to start again)");
  }
  if (exists) {
    try {
      std::size_t complete = 0;
      for (const Json& rec : ReadRecords(b.output, complete)) done.insert(rec.at("file").get<std::string>());
      if (complete < fs::file_size(b.output)) {
        fs::resize_file(b.output, complete);  // the torn last record: computed again
        std::cerr << "batch: " << b.output << ": dropped a torn last line\n";
      }
    } catch (const std::exception& e) {
      return Bad(std::string(e.what()) + " (--resume needs a file written by massprops batch)");
    }
  }
  std::vector<std::size_t> todo;
  for (std::size_t i : mine) {
    if (done.count(all[i]) > 0) {
      ++summary.skipped;
    } else {
      todo.push_back(i);
    }
  }
  const int fd = ::open(b.output.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) {
    massprops::app::PrintError(b.output + ": cannot open for appending (" + std::strerror(errno) + ")");
    return 1;
  }
  // Each file's picture: its stem, with its index where stems repeat.
  std::vector<std::string> pictures;
  if (!b.pictures.empty()) {
    try {
      fs::create_directories(b.pictures);
    } catch (const std::exception& e) {
      ::close(fd);
      massprops::app::PrintError(std::string("--pictures: ") + e.what());
      return 1;
    }
    std::map<std::string, int> stems;
    for (const std::string& f : all) ++stems[fs::path(f).stem().string()];
    for (std::size_t i = 0; i < all.size(); ++i) {
      const std::string stem = fs::path(all[i]).stem().string();
      pictures.push_back((fs::path(b.pictures) / (stems[stem] > 1 ? stem + "-" + std::to_string(i) : stem)).string() +
                         b.picture_extension);
    }
  }
  const int cores = massprops::ThreadCount(0);
  const int jobs = massprops::ThreadCount(b.jobs);
  LoadOptions load = b.load;
  if (!b.threads_given) load.num_threads = std::max(1, cores / jobs);
  const bool tty = !b.quiet && ::isatty(STDERR_FILENO) != 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  bool write_failed = false;
  try {
    // A process computes a run of files (starting one per file cost more than the file); a crash
    // or a timeout still ends only the file it happened on.
    RunIsolatedInRuns(
        todo.size(), jobs, b.timeout_seconds, kFilesPerProcess,
        [&](std::size_t k) {
          return ComputeRecord(all[todo[k]], todo[k], all.size(), load, pictures.empty() ? "" : pictures[todo[k]]);
        },
        [&](std::size_t k, IsolatedOutcome&& o) {
          const std::size_t i = todo[k];
          const Json rec = Json::parse(RecordOf(all[i], i, all.size(), std::move(o), b.timeout_seconds));
          summary.Add(rec);
          const std::string line = rec.dump() + "\n";  // one write: a whole record, or (if cut) a torn line
          if (!write_failed && ::write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
            write_failed = true;
          }
          if (tty) {
            const double s = elapsed();
            const double rate = static_cast<double>(k + 1) / std::max(s, 1e-9);
            std::fprintf(stderr, "\rbatch: %zu/%zu files, %.1f files/s, ~%.0f s left\033[K", k + 1, todo.size(), rate,
                         static_cast<double>(todo.size() - k - 1) / rate);
          }
        });
  } catch (const std::exception& e) {
    ::close(fd);
    std::cerr << (tty ? "\n" : "") << "error: batch: " << massprops::app::OneLine(e.what()) << "\n";
    return 1;
  }
  if (::close(fd) != 0) write_failed = true;
  if (tty) std::cerr << "\r\033[K";
  const double seconds = elapsed();
  if (!b.quiet) std::cerr << summary.ToText(seconds) << "\n";
  if (b.summary_json) std::cout << summary.ToJson(seconds).dump(2) << "\n";
  if (write_failed) {
    massprops::app::PrintError(b.output + ": a record could not be written (disk full?); --resume goes on");
    return 1;
  }
  return 0;
}

int RunMerge(const std::string& output, const std::vector<std::string>& shards) {
  if (shards.empty()) return Bad("merge needs OUT and at least one SHARD file");
  try {
    report::CheckOutputPath(output, shards);
  } catch (const std::exception& e) {
    return Bad(std::string("merge: ") + e.what());
  }
  std::map<std::size_t, Json> by_index;
  std::size_t of = 0;
  std::vector<std::string> repeated;
  for (const std::string& shard : shards) {
    std::size_t complete = 0;
    std::vector<Json> records;
    try {
      if (!fs::is_regular_file(shard)) throw std::runtime_error(shard + ": no such file");
      records = ReadRecords(shard, complete);
    } catch (const std::exception& e) {
      massprops::app::PrintError(std::string("merge: ") + e.what());
      return 1;
    }
    for (Json& rec : records) {
      if (!rec.contains("index") || !rec.contains("of")) {
        massprops::app::PrintError(std::string("merge: ") + shard +
                                   ": a record without index and of (not from massprops batch)");
        return 1;
      }
      const std::size_t n = rec["of"], i = rec["index"];
      if (of != 0 && n != of) {
        massprops::app::PrintError(std::string("merge: ") + shard + " comes from a run over " + std::to_string(n) +
                                   " files, another shard from " + std::to_string(of) + ": not the same input");
        return 1;
      }
      of = n;
      if (by_index.count(i) > 0) repeated.push_back(rec["file"]);
      by_index[i] = std::move(rec);
    }
  }
  if (!repeated.empty()) {
    massprops::app::PrintError(std::string("merge: ") + std::to_string(repeated.size()) +
                               " files have more than one record (the first: " + repeated[0] +
                               "); were shards given twice, or overlapping --shard values used?");
    return 1;
  }
  if (by_index.size() != of) {
    std::size_t first_missing = 0;
    while (by_index.count(first_missing) > 0) ++first_missing;
    massprops::app::PrintError("merge: " + std::to_string(of - by_index.size()) + " of " + std::to_string(of) +
                               " files have no record (the first is number " + std::to_string(first_missing) +
                               " in sorted order): a shard is missing or unfinished (--resume finishes it)");
    return 1;
  }
  std::string text;
  for (const auto& [i, rec] : by_index) text += rec.dump() + "\n";
  try {
    report::WriteFileAtomically(output, text);
  } catch (const std::exception& e) {
    massprops::app::PrintError(e.what());
    return 1;
  }
  return 0;
}

}  // namespace massprops::cli
