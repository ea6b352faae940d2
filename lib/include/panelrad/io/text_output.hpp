#pragma once
// Output files are written as a set: all of them, or none (the previous ones stay untouched).
//
// Each file of a set is first written completely to a new temporary beside it,
// PATH.tmp.<pid>.<random> (created with O_CREAT | O_EXCL, so no existing file is ever opened),
// flushed and fsync'ed, and every step's result checked (a full disk fails here). Only when all of
// them are written are they renamed over their paths, one after another; the directories are then
// fsync'ed. Before the renames every previous file is hard-linked to PATH.old.<pid>.<random>, so a
// rename that fails part-way (the target is a directory, the directory cannot grow) restores the
// files already replaced: the set is either wholly new or wholly previous. On failure every
// temporary is removed and std::runtime_error names the path and the system's reason.
//
// Signals: install_output_signal_handlers() makes SIGINT, SIGTERM and SIGHUP remove the
// temporaries in progress and then terminate the process by the same signal (exit status 128 +
// signal in a shell). A signal that arrives during the renames is held until the set is in place.
// Left behind are only what no handler can see: on SIGKILL or power loss, the temporaries (and,
// during the renames, the PATH.old.* links) of the run, never a mixed set without them.
#include <string>
#include <vector>

namespace panelrad {

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  /// Removes the temporaries of a set that was not committed.
  ~OutputSet();

  /// Writes `contents` to a new temporary beside `path`. On failure removes all temporaries of
  /// this set and throws std::runtime_error naming `path`; a path given twice is
  /// std::invalid_argument.
  void add(const std::string& path, const std::string& contents);

  /// Renames every temporary over its path (see above). Throws std::runtime_error naming the path
  /// that failed, after restoring the previous files; the set is empty afterwards either way.
  void commit();

  /// The paths added so far, in order.
  std::vector<std::string> paths() const;

 private:
  struct File {
    std::string path, temporary;
    int slot;  // index in the signal handlers' list of temporaries, -1 when none
  };
  std::vector<File> files_;
  void discard() noexcept;
};

/// Writes one file as a set of one.
void write_file_atomically(const std::string& path, const std::string& contents);

/// Checks, before any long work, that `path` can be written as an output: its directory exists
/// and takes a new file (a uniquely named temporary, created with O_EXCL and removed again, so an
/// existing file such as PATH.probe is never touched), and `path` is not a directory. Throws
/// std::runtime_error naming `path` and the reason.
void check_output_path(const std::string& path);

/// Installs handlers for SIGINT, SIGTERM and SIGHUP (unless the signal is ignored, as under
/// nohup) that remove the temporaries of every output set in progress, then re-raise the signal
/// with its default action. Idempotent.
void install_output_signal_handlers();

}  // namespace panelrad
