// OutputFiles: a run's outputs are written into a private staging folder beside the output
// folder and moved into it (one rename per entry) only when the whole run succeeded, so a
// failed run leaves no partial output files and a reader never sees a half-written one.
// Outputs of an earlier run in the same folder that this run does not produce (e.g. after
// --until) are removed, so the folder always holds one consistent run.
#pragma once

#include <memory>
#include <string>

#include "geometry/status.h"

namespace pqlayout {

class OutputFiles {
 public:
  // Prepares staging for final_dir (creates final_dir's parent folders if needed).
  static Status Open(const std::string& final_dir, std::unique_ptr<OutputFiles>* out);
  ~OutputFiles();  // removes the staging folder unless committed

  // Where to write `relative` (e.g. "fields/faces.csv"); its folders are created.
  std::string Path(const std::string& relative);
  Status WriteText(const std::string& relative, const std::string& content);
  // Moves every staged entry into the output folder.
  Status Commit();

  const std::string& final_dir() const { return final_dir_; }

 private:
  OutputFiles(std::string final_dir, std::string staging_dir)
      : final_dir_(std::move(final_dir)), staging_dir_(std::move(staging_dir)) {}
  std::string final_dir_, staging_dir_;
  bool committed_ = false;
};

}  // namespace pqlayout
