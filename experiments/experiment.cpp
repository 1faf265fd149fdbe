#include "experiment.hpp"

#include "figure.hpp"

#include "contact_ode/integrators/method_registry.hpp"
#include "contact_ode/integrators/run_result.hpp"
#include "process.hpp"
#include "ranks.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <stdexcept>
#include <tuple>

namespace contact {

Experiment::Experiment(std::string name, std::string description, std::string default_out)
    : cli::Options(std::move(name), std::move(description)), out_(std::move(default_out)) {
  add("--out", out_, "output directory (replaced whole when the run succeeds)");
}

Experiment::~Experiment() = default;

int Experiment::run_body(int argc, char** argv, const std::function<void(OutputSet&)>& body) {
  ranks_ = std::make_unique<Ranks>(argc, argv);
  if (const int code = parse(argc, argv); code >= 0) return code;
  if (const auto err = check_output_dir(out_, program()); !err.empty()) {
    std::cerr << program() << ": " << err << "\n";
    return cli::kExitBadInput;
  }
  require_scratch_location();  // figures are drawn there
  const auto start = std::chrono::steady_clock::now();
  OutputSet outputs;
  body(outputs);                      // exceptions go to guarded_main: exit 2 for bad input, 1 otherwise
  if (ranks_->rank() != 0) return 0;  // rank 0 writes
  draw_figures(outputs);              // gnuplot's failure: exit 1 through guarded_main
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outputs.add("meta.json", run_meta_json(program(), values_json(),
                                         std::vector<std::string>(argv, argv + argc), wall, ranks_->size()));
  try {
    outputs.write(out_, program());
  } catch (const std::exception& e) {
    std::cerr << program() << ": " << e.what() << "\n";
    return cli::kExitFailure;
  }
  fmt::print("\nwrote {} files to {} ({:.2f} s)\n", outputs.files().size(), out_, wall);
  return 0;
}

std::optional<std::vector<nlohmann::json>> Experiment::share(
    std::size_t count, const std::function<nlohmann::json(std::size_t)>& run_case) {
  const auto size = static_cast<std::size_t>(ranks_->size()), rank = static_cast<std::size_t>(ranks_->rank());
  // This rank's cases as [[i, result], ...]; a failure ends its share as {"index", "error", "bad_input"}.
  nlohmann::json mine = nlohmann::json::array();
  for (std::size_t i = rank; i < count; i += size) {
    try {
      mine.push_back({i, run_case(i)});
    } catch (const std::exception& e) {
      if (size == 1) throw;
      mine.push_back({{"index", i},
                      {"error", e.what()},
                      {"bad_input", dynamic_cast<const std::invalid_argument*>(&e) != nullptr}});
      break;
    }
  }
  if (size == 1) {
    std::vector<nlohmann::json> results;
    for (auto& item : mine) results.push_back(std::move(item[1]));
    return results;
  }
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(mine);
  const auto parts = ranks_->gather(std::string(bytes.begin(), bytes.end()));
  if (rank != 0) return std::nullopt;
  std::vector<nlohmann::json> results(count);
  const nlohmann::json* first_failure = nullptr;
  std::vector<nlohmann::json> all;
  for (const auto& part : parts) all.push_back(nlohmann::json::from_cbor(part.begin(), part.end()));
  for (const auto& share : all)
    for (const auto& item : share) {
      if (item.is_object()) {
        if (!first_failure || item["index"] < (*first_failure)["index"]) first_failure = &item;
      } else {
        results[item[0].get<std::size_t>()] = item[1];
      }
    }
  if (first_failure) {
    const auto what = (*first_failure)["error"].get<std::string>();
    if ((*first_failure)["bad_input"].get<bool>()) throw std::invalid_argument(what);
    throw std::runtime_error(what);
  }
  return results;
}

std::string failure_text(const RunResult& r) {
  return fmt::format("{} at t = {:.9g} s: {}", to_string(r.status), r.t_reached, r.message);
}

namespace {
std::string failure(const RunResult& r, const std::string& what) { return what + ": " + failure_text(r); }
}  // namespace

RunResult require(RunResult r, const std::string& what) {
  if (!r.ok()) throw std::runtime_error(failure(r, what));
  return r;
}

bool report(const RunResult& r, const std::string& what) {
  if (!r.ok()) std::cerr << failure(r, what) << "\n";
  return r.ok();
}

void refuse_dt_beyond_work_limit(const std::vector<PlannedRun>& runs, const std::string& option) {
  const PlannedRun* worst = nullptr;
  double least = 0;  // the dt the worst run needs: its work goes as 1 / dt
  for (const PlannedRun& run : runs) {
    const SolveOptions span{.t_end = run.t_end};
    if (!work_refusal(run.method, span)) continue;
    const double needs =
        run.method.dt * fixed_step_work(run.method, span) / static_cast<double>(span.limits.max_steps);
    if (needs > least) std::tie(worst, least) = std::pair{&run, needs};
  }
  if (!worst) return;
  const SolveOptions span{.t_end = worst->t_end};
  throw std::invalid_argument(fmt::format(
      "{0}: value '{1}' makes {2} over {3:g} s take {4}; accepted {0} >= {5:g}", option, worst->method.dt,
      worst->what, worst->t_end, *work_refusal(worst->method, span), cli::rounded_up(least)));
}

bool reads_option(const std::string& method, const std::string& option) {
  const MethodInfo& info = method_info(method);
  if (option == "--k" || option == "--law") return info.uses_contact_law;
  std::string setting = option.substr(2);  // --max-steps is the setting max_steps
  std::replace(setting.begin(), setting.end(), '-', '_');
  return std::find(info.settings.begin(), info.settings.end(), setting) != info.settings.end();
}

void note_unread_options(const std::string& program, const cli::Options& app,
                         const std::vector<std::string>& methods, const std::vector<std::string>& options) {
  const auto read_by_one = [&](const std::string& option) {
    return std::any_of(methods.begin(), methods.end(),
                       [&](const auto& m) { return reads_option(m, option); });
  };
  std::vector<std::string> taken;  // the options the methods read
  std::copy_if(options.begin(), options.end(), std::back_inserter(taken), read_by_one);
  for (const auto& option : options)
    if (app.given(option) && !read_by_one(option))
      fmt::print(
          stderr, "{}: note: {} has no effect on {}, which read{} {}\n", program, option,
          fmt::join(methods, ", "), methods.size() == 1 ? "s" : "",
          taken.empty() ? std::string("none of these options") : fmt::format("{}", fmt::join(taken, ", ")));
}

nlohmann::json row_to_json(const std::vector<Table::Cell>& row) {
  nlohmann::json cells = nlohmann::json::array();
  for (const auto& cell : row) std::visit([&](const auto& v) { cells.push_back(v); }, cell);
  return cells;
}

std::vector<Table::Cell> row_from_json(const nlohmann::json& cells) {
  std::vector<Table::Cell> row;
  for (const auto& c : cells)
    row.push_back(c.is_string()           ? Table::Cell(c.get<std::string>())
                  : c.is_number_integer() ? Table::Cell(c.get<long>())
                                          : Table::Cell(c.get<double>()));
  return row;
}

}  // namespace contact
