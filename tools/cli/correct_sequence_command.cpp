// posekit correct-sequence: every frame of an animation corrected against one reference, the
// corrections blended in time, each frame written under its own name. Each frame's own correction is
// kept in DIR/.posekit-partial as it finishes, so that --resume does not redo it; the folder goes
// once every frame is written.
#include "cli_common.hpp"
#include "commands.hpp"
#include "correction_flags.hpp"
#include "frame_progress.hpp"
#include "html_page.hpp"
#include "html_report_option.hpp"
#include "job_pages.hpp"
#include "sequence_report_json.hpp"

#include <posekit/correct_sequence.hpp>
#include <posekit/device_registry.hpp>
#include <posekit/error.hpp>
#include <posekit/mesh_io.hpp>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

namespace posekit::cli {
namespace {

namespace fs = std::filesystem;

struct SequenceCommandOptions {
  std::string reference;
  std::vector<std::string> frames;
  std::string frames_from;
  std::string output;
  std::string report;
  std::string html;
  bool resume = false;
  bool no_carry = false;
  double smoothing_frames = SequenceCorrectionOptions{}.smoothing_frames;
  CorrectionFlags flags;
};

constexpr const char* kPartialFolder = ".posekit-partial";
constexpr const char* kRunFile = "run.json";

// Frame files named in `list`, one per line ('#' starts a comment); a relative name is taken from
// the list's own folder.
std::vector<std::string> read_frame_list(const std::string& list) {
  std::ifstream stream(list);
  if (!stream) throw InputError(list, 0, "cannot open the frame list");
  std::vector<std::string> frames;
  std::string line;
  while (std::getline(stream, line)) {
    line = line.substr(0, line.find('#'));
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    const size_t last = line.find_last_not_of(" \t\r");
    const fs::path name = line.substr(first, last - first + 1);
    frames.push_back((name.is_absolute() ? name : fs::path(list).parent_path() / name).string());
  }
  if (frames.empty()) throw InputError(list, 0, "the frame list names no frame");
  return frames;
}

// What the kept corrections depend on: the reference's coordinates and every correction option.
std::string run_fingerprint(const Mesh& reference, const SequenceCorrectionOptions& sequence) {
  const CorrectionOptions& options = sequence.frame;
  std::ostringstream text;
  text << std::setprecision(17) << reference.vertices.rows() << ' ' << reference.faces.rows();
  for (Eigen::Index v = 0; v < reference.vertices.rows(); ++v) {
    text << ' ' << reference.vertices(v, 0) << ' ' << reference.vertices(v, 1) << ' ' << reference.vertices(v, 2);
  }
  const size_t geometry = std::hash<std::string>{}(text.str());
  std::ostringstream out;
  out << std::setprecision(17) << "reference " << geometry << " key_frames " << options.key_frames
      << " constraint_times " << options.constraint_times << " exclusion_rings " << options.exclusion_rings
      << " candidates " << options.candidates << " centers_per_round " << options.centers_per_round
      << " error_factor " << options.error_factor << " max_centers " << options.max_centers << " blocked_update "
      << options.blocked_update << " rtol " << options.integration.relative_tolerance << " atol "
      << options.integration.absolute_tolerance << " time_scale " << options.time_scale << " drift_passes "
      << options.drift_passes << " intersection_substeps " << options.intersection_substeps << " exclusion_window "
      << options.exclusion_window << " whole_mesh " << options.whole_mesh << " collar_rings " << options.collar_rings
      << " reproduction_rings " << options.reproduction_rings << " blend_rings " << options.blend_rings
      << " separation_tolerance " << options.separation_tolerance << " excluded";
  for (const int v : options.excluded_vertices) out << ' ' << v;
  out << " carry " << sequence.carry_corrections << " disabled";
  for (const std::string& stage : options.disabled_stages) out << ' ' << stage;
  return out.str();
}

void run_correct_sequence(const SequenceCommandOptions& options) {
  if (!options.html.empty()) report::check_report_destination(options.html, "--html");
  std::vector<std::string> files = options.frames;
  if (!options.frames_from.empty()) {
    const std::vector<std::string> listed = read_frame_list(options.frames_from);
    files.insert(files.end(), listed.begin(), listed.end());
  }
  if (files.empty()) throw ArgumentError("correct-sequence: no frame given (FRAME... or --frames-from LIST)");
  const fs::path folder = options.output;
  // Output names first: every frame's own file name in DIR, distinct, not the frame itself.
  std::vector<std::string> names;
  std::map<std::string, std::string> first_with_name;
  for (const std::string& file : files) {
    const std::string name = fs::path(file).filename().string();
    mesh_format_from_extension(file);
    const auto [found, inserted] = first_with_name.emplace(name, file);
    if (!inserted) throw InputError(file, 0, "has the same file name as " + found->second + " (one output each in " + folder.string() + ")");
    std::error_code error;
    if (fs::equivalent(folder / name, file, error)) {
      throw InputError(file, 0, "would be overwritten by its own result (choose another output folder)");
    }
    names.push_back(name);
  }
  std::vector<std::string> warnings;
  const Mesh reference = read_mesh(options.reference, &warnings);
  std::vector<Eigen::MatrixX3d> frames;
  frames.reserve(files.size());
  for (const std::string& file : files) {
    Mesh frame = read_mesh(file, &warnings);
    check_same_connectivity(reference, options.reference, frame, file);
    frames.push_back(std::move(frame.vertices));
  }
  print_warnings(warnings);
  SequenceCorrectionOptions sequence;
  sequence.frame = correction_options(options.flags, static_cast<int>(reference.vertices.rows()));
  sequence.smoothing_frames = options.smoothing_frames;
  sequence.carry_corrections = !options.no_carry;
  std::unique_ptr<Device> device = create_device(options.flags.device);

  // The output folder and the kept corrections of an earlier run.
  const fs::path partial = folder / kPartialFolder;
  std::error_code error;
  fs::create_directories(partial, error);
  if (error) throw InputError(folder.string(), 0, "cannot create the output folder: " + error.message());
  const std::string fingerprint = run_fingerprint(reference, sequence);
  std::vector<Eigen::MatrixX3d> earlier(frames.size());
  int reused = 0;
  if (options.resume && fs::exists(partial / kRunFile)) {
    std::ifstream stream(partial / kRunFile);
    const std::string kept((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    if (kept != fingerprint) {
      throw InputError((partial / kRunFile).string(), 0,
                       "was written for another reference or other correction options; run without --resume");
    }
    for (size_t t = 0; t < frames.size(); ++t) {
      const fs::path file = partial / (names[t] + ".ply");
      if (!fs::exists(file)) continue;
      Mesh own = read_mesh(file);
      check_same_connectivity(reference, options.reference, own, file.string());
      earlier[t] = std::move(own.vertices);
      ++reused;
    }
  } else {
    for (const fs::directory_entry& entry : fs::directory_iterator(partial)) fs::remove(entry.path());
    write_text_atomically(partial / kRunFile, fingerprint);
  }

  FrameProgress progress("correct-sequence", options.flags.progress_lines);
  SequenceCallbacks callbacks;
  callbacks.progress = [&](int done, int total) { progress.update(done, total, std::min(done, reused)); };
  callbacks.frame_corrected = [&](int frame, const Eigen::MatrixX3d& own) {
    write_mesh(partial / (names[static_cast<size_t>(frame)] + ".ply"), Mesh{own, reference.faces});
  };
  SequenceReport report;
  const std::vector<FrameCorrection> results =
      correct_sequence(reference.vertices, frames, reference.faces, *device, sequence, &report, callbacks, &earlier);
  progress.finish();

  for (size_t t = 0; t < results.size(); ++t) {
    const fs::path file = folder / names[t];
    if (results[t].error.empty()) {
      write_mesh(file, Mesh{results[t].vertices, reference.faces});
    } else {
      fs::remove(file, error);  // a result of an earlier run would not match this one's neighbours
      std::cerr << "posekit: error: " << files[t] << ": not corrected: " << results[t].error << "\n";
    }
  }
  const std::string device_name = device->info().backend + ": " + device->info().name;
  if (!options.report.empty()) {
    write_text_atomically(options.report, sequence_report_json(report, results, names, device_name).dump(2) + "\n");
  }
  if (!options.html.empty()) {
    std::vector<Eigen::MatrixX3d> shown;  // a frame not corrected is shown as its target
    shown.reserve(results.size());
    for (size_t t = 0; t < results.size(); ++t) shown.push_back(results[t].error.empty() ? results[t].vertices : frames[t]);
    report::write_html_report(options.html, report::sequence_page(reference.vertices, frames, shown, reference.faces, names,
                                                                  report, command_line()));
  }
  if (report.failed_frames == 0) fs::remove_all(partial, error);
  const SequenceCoherence& c = report.coherence;
  std::cout << std::fixed << std::setprecision(2) << folder.string() << ": " << report.frames << " frames, "
            << report.corrected_frames << " corrected (" << report.carried_frames << " by the previous frame's correction), " << report.touched_frames << " changed, "
            << report.frames_with_new_faces << " with new intersecting faces; largest change of a correction between "
            << "frames " << 100.0 * c.largest_offset_change << " % of the diagonal (" << 100.0 * c.largest_offset_change_alone
            << " % frame by frame); " << report.seconds << " s on " << device_name << "\n";
  if (report.failed_frames > 0) {
    throw Error(std::to_string(report.failed_frames) + " of " + std::to_string(report.frames) +
                " frames not corrected (named above; --resume retries them alone)");
  }
}

}  // namespace

void add_correct_sequence_command(CLI::App& app, int& exit_status) {
  auto options = std::make_shared<SequenceCommandOptions>();
  auto* command = app.add_subcommand(
      "correct-sequence",
      "Remove the self-intersections of every FRAME against the clean REFERENCE, coherently in time");
  command->add_option("REFERENCE", options->reference, "Clean reference pose")->required();
  command->add_option("FRAME", options->frames, "Frames in time order, same connectivity");
  command->add_option("--frames-from", options->frames_from,
                      "File naming the frames, one per line after those given (relative to its folder)");
  command->add_option("-o,--output", options->output, "Folder for the corrected frames, each under its own name")
      ->required();
  command->add_option("--report", options->report, "Write a JSON report of the sequence and every frame to this file");
  add_html_option(command, options->html);
  command->add_flag("--resume", options->resume,
                    "Reuse the frame corrections an interrupted run kept in the output folder");
  command->add_option("--smoothing", options->smoothing_frames,
                      "Standard deviation in frames of the blend of each correction with its neighbours' (0: none)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  command->add_flag("--no-carry", options->no_carry,
                    "Correct every frame that has new intersecting faces itself, without first trying the previous "
                    "frame's correction");
  add_correction_flags(command, options->flags);
  command->callback([options, &exit_status] { exit_status = run_guarded([&] { run_correct_sequence(*options); }); });
}

}  // namespace posekit::cli
