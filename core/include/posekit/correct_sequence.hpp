// Correction of a whole animation: every frame corrected against one clean reference, then the
// corrections (result minus target) made coherent in time, so that they ramp in before a contact
// and out after it instead of switching from one frame to the next. docs/correct-sequence.md
// describes the method, its options and its report.
#pragma once

#include <posekit/correct.hpp>
#include <posekit/device.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace posekit {

/// Parameters of correct_sequence().
struct SequenceCorrectionOptions {
  CorrectionOptions frame;  ///< the correction of each frame against the reference
  /// Standard deviation, in frames, of the Gaussian that blends each frame's correction with its
  /// neighbours' (>= 0; 0 keeps each frame's own correction). A frame that would gain intersecting
  /// faces from the blend gets back as much of its own correction as it needs.
  double smoothing_frames = 2.0;
  /// A frame with new intersecting faces first tries the previous frame's correction, scaled by a
  /// quarter, a half, three quarters and whole; it is corrected itself only when none of those frees
  /// it without stretching more faces than the previous result. false: every such frame alone.
  bool carry_corrections = true;
};

/// Frames on each side of a frame whose corrections its blend reads (three standard deviations,
/// rounded up): a part of a sequence blended with this many more frames on each side gives the same
/// frames as the whole sequence.
int blend_radius(double smoothing_frames);

/// One frame's outcome.
struct FrameCorrection {
  Eigen::MatrixX3d vertices;        ///< the result (#V by 3); empty when the frame failed
  bool touched = false;             ///< some vertex differs from the target
  bool corrected = false;           ///< the frame had new intersecting faces, so it was corrected
  bool reused = false;              ///< its own correction came from `earlier`, not from this run
  bool carried = false;             ///< its own correction is the previous frame's, scaled by `carried_scale`
  double carried_scale = 0;
  int stretched_faces = 0;          ///< of the result, as CorrectionReport's result counts them
  double seconds = 0;               ///< of its own correction
  std::string error;                ///< why its correction failed; empty when it did not
  int target_new_faces = 0;         ///< intersecting faces of the target not in the reference
  int new_faces = 0;                ///< of the result
  double own_share = 0;             ///< share of its own correction put back after the blend (0 to 1)
  double median_distance_to_target = 0;  ///< of the result's vertices, in the input's units
  double max_distance_to_target = 0;
  CorrectionReport report;          ///< of its own correction (when corrected, not carried, not reused)
};

/// Smoothness of the corrections over the sequence, measured over the vertices corrected in some
/// frame; the same figures for the frames corrected alone are given beside.
struct SequenceCoherence {
  int vertices = 0;                    ///< vertices moved in some frame
  /// Largest change of a vertex's correction between consecutive frames, in fractions of the
  /// reference's bounding-box diagonal.
  double largest_offset_change = 0;
  double largest_offset_change_alone = 0;
  /// 99th percentile and maximum of the second difference in time of those vertices' positions,
  /// over the target sequence's own (1: no acceleration added).
  double acceleration_p99_ratio = 0;
  double acceleration_max_ratio = 0;
  double acceleration_p99_ratio_alone = 0;
  double acceleration_max_ratio_alone = 0;
};

/// What correct_sequence() did.
struct SequenceReport {
  int frames = 0;
  int corrected_frames = 0;  ///< with new intersecting faces, corrected themselves or by a carried correction
  int carried_frames = 0;    ///< of those, by the previous frame's correction scaled
  int touched_frames = 0;    ///< differing from their target (corrected or reached by a neighbour's blend)
  int failed_frames = 0;
  int frames_with_new_faces = 0;  ///< results that still have new intersecting faces
  SequenceCoherence coherence;
  double bounding_box_diagonal = 0;  ///< of the reference
  double seconds = 0;                ///< wall time in all
  double correction_seconds = 0;     ///< of the frames' own corrections
  double coherence_seconds = 0;      ///< of the blend in time and its checks
};

/// Callbacks of correct_sequence(), each optional, called one at a time (runs of frames that need a
/// correction are corrected in parallel, so not always on the calling thread).
struct SequenceCallbacks {
  /// Frames whose own correction is done (or reused) out of all.
  std::function<void(int done, int total)> progress;
  /// A frame's own correction as it finishes, e.g. to keep it for resuming an interrupted run.
  std::function<void(int frame, const Eigen::MatrixX3d& own)> frame_corrected;
};

/// Corrects every one of `frames` (#V by 3 each) against the clean `reference` sharing the #F by 3
/// `faces`, then blends the corrections in time. Runs of consecutive frames with new intersecting
/// faces are independent of each other and corrected in parallel. `earlier`, when given, holds for each frame either
/// its own correction from an earlier run (reused, not recomputed) or an empty matrix. A frame whose
/// correction throws is reported in its entry and leaves the others unaffected; ArgumentError for
/// inconsistent input or options; DeviceError from the device.
std::vector<FrameCorrection> correct_sequence(const Eigen::Ref<const Eigen::MatrixX3d>& reference,
                                              const std::vector<Eigen::MatrixX3d>& frames,
                                              const Eigen::Ref<const Eigen::MatrixX3i>& faces, Device& device,
                                              const SequenceCorrectionOptions& options = {},
                                              SequenceReport* report = nullptr, const SequenceCallbacks& callbacks = {},
                                              const std::vector<Eigen::MatrixX3d>* earlier = nullptr);

}  // namespace posekit
