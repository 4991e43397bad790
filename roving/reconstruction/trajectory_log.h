// Tanks and Temples' camera files, as its toolbox's trajectory_io.py and registration.py read them:
// - a trajectory (.log; the reconstruction's, and the scene's <scene>_COLMAP_SfM.log): per camera
//   a line of metadata (ignored) and four lines of four numbers, its camera-to-world pose;
// - a mapping (<scene>_mapping_reference.txt): the count of reference frames, the count of all
//   frames, then per reference frame a line "i frame", frame counted from 1.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace roving {

// Throws roving::Error naming `path` and the line for a file that cannot be read, a pose row of
// other than four finite numbers, a camera cut short, or no camera.
std::vector<Eigen::Matrix4d> read_trajectory_log(const std::string& path);

// The frames, in order. Throws roving::Error naming `path` and the line for counts that are not
// whole numbers, a line of other than two, fewer lines than the first count, or a frame outside
// 1 to the second count.
std::vector<std::size_t> read_frame_mapping(const std::string& path);

}  // namespace roving
