// posekit: the command-line tool.
#include "commands.hpp"
#include "html_report_option.hpp"

#include <posekit/version.hpp>

#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"posekit: example-based processing of triangle-mesh poses"};
  app.set_version_flag("--version", std::string("posekit ") + posekit::kVersion);
  app.require_subcommand(1);
  int exit_status = 0;
  posekit::cli::add_devices_command(app, exit_status);
  posekit::cli::add_check_command(app, exit_status);
  posekit::cli::add_correct_command(app, exit_status);
  posekit::cli::add_correct_sequence_command(app, exit_status);
  posekit::cli::add_interpolate_command(app, exit_status);
  posekit::cli::add_deform_command(app, exit_status);
  posekit::cli::add_register_command(app, exit_status);
  posekit::cli::add_convert_command(app, exit_status);
  posekit::cli::add_generate_command(app, exit_status);
  posekit::cli::add_demo_command(app, exit_status);
  posekit::cli::set_command_line(argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const CLI::ParseError& error) {
    // One line for a usage error; --help has the rest.
    std::cerr << "posekit: error: " << error.what() << " (see posekit --help)\n";
    return 2;
  }
  return exit_status;
}
