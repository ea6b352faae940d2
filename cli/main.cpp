// panelrad command-line program: dispatches sub-commands (CLI11 sub-commands of one App).
// Built with PANELRAD_MPI, it runs as one rank of `mpirun -np K panelrad ...`: the ranks share
// each solve's rows (processes.hpp), rank 0 alone writes to standard output, and a failure on any
// rank ends every rank (MPI_Abort) with its message, so that none waits for it forever.
#include "commands.hpp"
#include "hints.hpp"
#include "options.hpp"
#include "processes.hpp"

#include <panelrad/support/version.hpp>
#if PANELRAD_MPI
#include <panelrad/mpi/mpi_communicator.hpp>
#endif

#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace {
const char* kUsage =
    "usage: panelrad <command> [options]\n"
    "commands:\n"
    "  check MESH | check --builtin cube|prism:K|tetrahedron|octahedron\n"
    "      validate a scene mesh (OFF or OBJ): convex (V = 1) or general (V computed)\n"
    "  cube [options]   the paper's cube example (Table 1; --help for options)\n"
    "  solve SCENE [options]   solve an OBJ+MTL or OFF+JSON scene, write CSV/PLY/VTK/PNG (--help)\n"
    "  viewfactors SCENE [options]   view factors between groups of surfaces, write CSV/NPY (--help)\n"
    "  thermal SCENE --bc FILE [options]   temperatures and heat fluxes, SI units, write CSV/VTK (--help)\n"
    "  version\n"
    "  help [COMMAND]\n";

std::string quoted(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += (s.empty() ? "'" : " '") + a + "'";
  return s;
}

/// The arguments no option or positional took, in command-line order (CLI11's own message
/// lists them in reverse): the first one as an unknown option, or as an unexpected argument
/// after the positional arguments already taken.
std::string describe_extras(const CLI::App& command, const std::vector<std::string>& extras) {
  const std::string& first = extras.front();
  std::string what;
  if (first.size() > 1 && first[0] == '-') {
    what = "unknown option '" + first + "'";
  } else {
    what = "unexpected argument '" + first + "'";
    for (const CLI::Option* p : command.get_options([](const CLI::Option* o) { return o->get_positional(); }))
      if (p->count() > 0) what += " after " + p->get_name() + " '" + p->results().front() + "'";
  }
  if (extras.size() > 1) what += " (not taken: " + quoted(extras) + ")";
  return what;
}
}  // namespace

int main(int argc, char** argv) {
  using panelrad::cli::Command;
#if PANELRAD_MPI
  // Under mpirun: one rank of the run. Started otherwise: alone, as the default build's program.
  std::optional<panelrad::MpiSession> mpi;
  std::unique_ptr<const panelrad::MpiCommunicator> world;
  if (panelrad::started_by_mpi_launcher()) {
    mpi.emplace(argc, argv);
    world = std::make_unique<const panelrad::MpiCommunicator>();
    panelrad::cli::set_shared_solve(world.get());
  }
  // Rank 0 alone writes the tables, summaries and usage texts; the others' standard output goes
  // nowhere (their standard error stays: a rank's failure is said by that rank).
  if (!panelrad::cli::writes_outputs() && !std::freopen("/dev/null", "w", stdout)) return 1;
  // A failed command on several ranks: its message, then every rank ends (exit status `code`).
  const auto fail = [&world](const std::string& message, int code) {
    if (world && world->size() > 1) world->abort(message, code);
    std::cerr << message;
    return code;
  };
#else
  const auto fail = [](const std::string& message, int code) {
    std::cerr << message;
    return code;
  };
#endif
  CLI::App panelrad{"", "panelrad"};
  panelrad::cli::set_usage(panelrad, kUsage);
  // One command; a further command name is then an argument of the first (an error).
  panelrad.require_subcommand(0, 1);
  const std::vector<Command> commands = {panelrad::cli::add_check(panelrad), panelrad::cli::add_cube(panelrad),
                                         panelrad::cli::add_solve(panelrad), panelrad::cli::add_view_factors(panelrad),
                                         panelrad::cli::add_thermal(panelrad)};
  const std::string version_line = "panelrad " + panelrad::version();
  CLI::App* version = panelrad.add_subcommand("version", "the program's version");
  CLI::App* help = panelrad.add_subcommand("help", "the commands, or one command's options");
  std::string help_topic;  // panelrad help COMMAND: that command's usage, as COMMAND --help
  help->add_option("COMMAND", help_topic)
      ->check(panelrad::cli::one_of({"check", "cube", "solve", "viewfactors", "thermal"}));
  panelrad.set_version_flag("--version", version_line);

  try {
    panelrad.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const std::vector<CLI::App*> given = panelrad.get_subcommands();
    const CLI::App& command = given.empty() ? panelrad : *given.front();
    if (dynamic_cast<const CLI::CallForVersion*>(&e)) {
      std::cout << e.what() << "\n";
      return 0;
    }
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {  // --help
      std::cout << command.help();
      return 0;
    }
    std::string message = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      std::vector<std::string> extras = command.remaining();
      if (extras.empty()) extras = panelrad.remaining();  // after "--", back at the top
      if (given.empty()) {
        std::cerr << "panelrad: unknown command '" << extras.front() << "'\n" << kUsage;
        return 2;
      }
      message = describe_extras(command, extras);
    }
    std::cerr << (given.empty() ? std::string("panelrad") : "panelrad " + command.get_name()) << ": " << message
              << "\n"
              << command.help();
    return 2;
  }
  if (version->parsed()) {
    std::cout << version_line << "\n";
    return 0;
  }
  if (help->parsed()) {
    std::cout << (help_topic.empty() ? std::string(kUsage) : panelrad.get_subcommand(help_topic)->help());
    return 0;
  }
  for (const Command& c : commands) {
    if (!c.app->parsed()) continue;
    const std::string name = c.app->get_name();
    try {
      const int status = c.run();
      if (status != 0) return fail("", status);  // the command said why
      return 0;
    } catch (const panelrad::cli::UsageError& e) {
      return fail("panelrad " + name + ": " + e.what() + "\n" + c.app->help(), 2);
    } catch (const std::exception& e) {
      std::string message = "panelrad " + name + ": error: " + e.what() + "\n";
      if (const std::string hint = panelrad::cli::hint_for(e); !hint.empty())
        message += "panelrad " + name + ": " + hint + "\n";
      return fail(message, 1);
    }
  }
  std::cerr << kUsage;  // no command
  return 2;
}
