// The arbor command line: registers the commands of app/commands/ with CLI11, runs the one asked
// for, and maps errors to exit codes (0 success, 1 the work failed, 2 bad input or usage).
#include <algorithm>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands/compare.h"
#include "app/commands/export.h"
#include "app/commands/grow.h"
#include "app/commands/inspect.h"
#include "app/commands/merge.h"
#include "app/commands/plan.h"
#include "app/commands/render.h"
#include "arbor/version.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "imaging/color.h"

namespace {

// Levenshtein distance, for "did you mean" on a mistyped command.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The message for a command line CLI11 refused: one form, "arbor: error: ...", with "did you
// mean" for a mistyped command.
void report_usage_error(const CLI::App& app, const CLI::ParseError& e, const std::string& first) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    names.push_back(sub->get_name());
  const bool known = std::find(names.begin(), names.end(), first) != names.end();
  if (first.empty() || first[0] == '-' || known) {
    std::fprintf(stderr, "arbor: error: %s (arbor %s--help)\n", e.what(),
                 known ? (first + " ").c_str() : "");
    return;
  }
  std::string list, near;
  for (const std::string& n : names) {
    list += (list.empty() ? "" : ", ") + n;
    if (near.empty() && edit_distance(first, n) <= 2) near = n;
  }
  std::fprintf(stderr, "arbor: error: unknown command '%s'%s; the commands are %s (arbor --help)\n",
               first.c_str(), near.empty() ? "" : (" (did you mean '" + near + "'?)").c_str(),
               list.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"arbor " ARBOR_VERSION_STRING
               ": grows trees from procedural models and renders them (physically based)"};
  app.set_version_flag(
      "--version", std::string("arbor ") + ARBOR_VERSION_STRING + " (commit " + ARBOR_COMMIT + ")");
  app.require_subcommand(1);
  arbor::app::GrowRequest grow;
  arbor::app::RenderRequest render;
  arbor::app::CompareRequest compare;
  arbor::app::MergeRequest merge;
  arbor::app::PlanRequest plan;
  arbor::app::ExportRequest exp;
  arbor::app::InspectRequest inspect;
  CLI::App* grow_cmd = arbor::app::add_grow_command(app, grow);
  CLI::App* render_cmd = arbor::app::add_render_command(app, render);
  CLI::App* compare_cmd = arbor::app::add_compare_command(app, compare);
  CLI::App* merge_cmd = arbor::app::add_merge_command(app, merge);
  CLI::App* plan_cmd = arbor::app::add_plan_command(app, plan);
  CLI::App* export_cmd = arbor::app::add_export_command(app, exp);
  CLI::App* inspect_cmd = arbor::app::add_inspect_command(app, inspect);

  arbor::remove_temporaries_on_signal();
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    report_usage_error(app, e, argc > 1 ? argv[1] : "");
    return 2;
  }

  try {
    // The OCIO config of this run: $OCIO, or arbor's own beside the executable.
    render.ocio_config = compare.ocio_config = merge.ocio_config = exp.ocio_config =
        inspect.ocio_config = arbor::imaging::default_ocio_config();
    if (*grow_cmd) return arbor::app::grow_command(grow);
    if (*render_cmd) return arbor::app::render_command(render);
    if (*compare_cmd) return arbor::app::compare_command(compare);
    if (*merge_cmd) return arbor::app::merge_command(merge);
    if (*export_cmd) return arbor::app::export_command(exp);
    if (*plan_cmd) return arbor::app::plan_command(plan);
    if (*inspect_cmd) return arbor::app::inspect_command(inspect);
  } catch (const arbor::InputError& e) {
    std::fprintf(stderr, "%s%s\n", e.where().path.empty() ? "arbor: " : "", e.what());
    return 2;
  } catch (const arbor::RuntimeFailure& e) {
    std::fprintf(stderr, "arbor: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "arbor: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "arbor: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
