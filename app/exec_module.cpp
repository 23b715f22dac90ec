#include "app/exec_module.hpp"

#include <algorithm>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "app/child_process.hpp"
#include "core/error.hpp"
#include "core/exec_protocol.hpp"
#include "core/file_status.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::size_t kFlushBytes = 64u << 10;  // events are batched: one write per 64 KiB

class ExecModule : public SlamModule {
 public:
  ExecModule(ExecDeclaration declaration, json params)
      : declaration_(std::move(declaration)), params_(std::move(params)) {}

  void Start(const StreamHeader& header) override {
    try {
      child_.emplace(ChildCommand{declaration_.command, declaration_.working_dir, declaration_.idle_timeout_s});
    } catch (const ChildError& e) {
      throw std::runtime_error(declaration_.name + ": " + e.what());
    }
    buffer_ = ExecHeaderLine(header, declaration_.name, params_, declaration_.needs.map);
    buffer_ += '\n';
  }
  void OnOdometry(const OdometryEvent& e) override { Add(e, e.t_s); }
  void OnLaserScan(const LaserScanEvent& e) override { Add(e, e.t_s); }
  void OnLandmarks(const LandmarkEvent& e) override { Add(e, e.t_s); }
  void OnGyro(const GyroEvent& e) override { Add(e, e.t_s); }

  Estimate Finish() override {
    buffer_ += kFinishLine;
    Guard([&] {
      Flush();
      const std::string exit = child_->CloseAndWait(on_line_);
      if (!parser_.done())
        throw ChildError("exited before {\"type\":\"done\"} (" + (exit.empty() ? "exit status 0" : exit) +
                         ", after stdout line " + std::to_string(child_->stdout_lines()) + ")");
      if (!exit.empty()) throw ChildError(exit + " after {\"type\":\"done\"}");
    });
    return parser_.TakeEstimate();
  }

 private:
  template <class Event>
  void Add(const Event& e, double t_s) {
    AppendEventLine(e, buffer_);
    latest_t_s_ = t_s;
    if (buffer_.size() >= kFlushBytes) Guard([&] { Flush(); });
  }
  void Flush() {
    child_->Write(buffer_, on_line_);
    buffer_.clear();
  }
  /// Runs `f`; any failure kills the child and is rethrown naming the module, with the
  /// child's stderr tail (ModuleDiverged stays ModuleDiverged: status `diverged`).
  template <class F>
  void Guard(F&& f) {
    try {
      f();
    } catch (const ModuleDiverged& e) {
      throw ModuleDiverged(Describe(e.what()));
    } catch (const std::exception& e) {
      throw std::runtime_error(Describe(e.what()));
    }
  }
  std::string Describe(const std::string& problem) {
    child_->Kill();
    std::string tail = child_->StderrTail();
    while (!tail.empty() && tail.back() == '\n') tail.pop_back();
    return declaration_.name + " (" + declaration_.file + "): " + problem +
           (tail.empty() ? "; stderr: (empty)" : "; stderr tail:\n" + tail);
  }

  ExecDeclaration declaration_;
  json params_;
  std::optional<ChildProcess> child_;
  std::string buffer_;
  double latest_t_s_ = 0.0;
  long line_number_ = 0;
  ExecAnswerParser parser_;
  const ChildProcess::LineHandler on_line_ = [this](std::string_view line) {
    parser_.ParseLine(line, ++line_number_, latest_t_s_);
  };
};

}  // namespace

std::vector<const ModuleInfo*> ExecModulesOnPath() {
  std::vector<std::string> names;
  for (const auto& folder : ExecPathFolders()) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec))
      if (entry.path().extension() == ".yaml") names.push_back("exec:" + entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::vector<const ModuleInfo*> out;
  for (const auto& name : names) {
    try {
      out.push_back(&FindExecModule(name));
    } catch (const InputError&) {  // not a declaration: `--algo` on it gives the error
    }
  }
  return out;
}


ModuleInfo ExecModuleInfo(const ExecDeclaration& declaration) {
  ModuleInfo info;
  info.name = declaration.name;
  info.description = declaration.description.empty() ? "exec module " + declaration.file : declaration.description;
  info.needs = declaration.needs;
  info.baseline = declaration.baseline;
  info.params = [declaration] {
    std::vector<ParamInfo> list;
    BindExecParams(declaration, nullptr, &list);
    return list;
  };
  info.create = [declaration](const ParamOverrides& overrides) -> std::unique_ptr<SlamModule> {
    return std::make_unique<ExecModule>(declaration, BindExecParams(declaration, &overrides, nullptr));
  };
  return info;
}


namespace {

/// Every exec module loaded so far (declaration files, `--exec` on the command line).
struct ExecModuleCache {
  std::mutex mutex;
  std::deque<ModuleInfo> loaded;                    // stable references
  std::map<std::string, const ModuleInfo*> by_name;  // canonical and as-asked names
  std::map<std::string, std::string> file_of;        // canonical name -> declaration file
};

ExecModuleCache& Cache() {
  static ExecModuleCache cache;
  return cache;
}

/// Adds `declaration` (caller holds the lock); a second, different one of that name is an error.
const ModuleInfo* Add(ExecModuleCache& c, const ExecDeclaration& declaration, const std::string& asked_as) {
  const ModuleInfo* info = nullptr;
  if (const auto it = c.by_name.find(declaration.name); it != c.by_name.end()) {
    const std::string& known = c.file_of.at(declaration.name);
    const bool same = known == declaration.file ||
                      SameFile(known, declaration.file);
    if (!same)
      throw InputError(asked_as, 0,
                       "two declarations are both named " + declaration.name + ": " + known + " and " +
                           declaration.file,
                       "rename one (a file's module name is its file name)");
    info = it->second;
  } else {
    info = &c.loaded.emplace_back(ExecModuleInfo(declaration));
    c.file_of[declaration.name] = declaration.file;
  }
  c.by_name[declaration.name] = info;
  return info;
}

}  // namespace

const ModuleInfo& FindExecModule(const std::string& module_name) {
  ExecModuleCache& c = Cache();
  const std::lock_guard lock(c.mutex);
  if (const auto it = c.by_name.find(module_name); it != c.by_name.end()) return *it->second;
  const ModuleInfo* info = Add(c, LoadExecDeclaration(FindExecDeclaration(module_name)), "--algo " + module_name);
  c.by_name[module_name] = info;
  return *info;
}

void DeclareExecModule(const ExecDeclaration& declaration) {
  ExecModuleCache& c = Cache();
  const std::lock_guard lock(c.mutex);
  Add(c, declaration, "--exec " + declaration.name);
}

}  // namespace slambox
