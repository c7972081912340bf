#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "project/config.h"
#include "lang/syntax.h"

namespace lwc {

// A file to lint, or a path that could not be walked (error set).
struct InputFile {
  std::filesystem::path path;
  std::string display;  // as the user would write it: relative to the argument given
  std::shared_ptr<const ProjectConfig> config;
  std::string error;
  size_t argument = 0;  // which command-line path it came from
  std::optional<std::string> content;  // given instead of read from `path` (standard input)
  // Not linted: its extension is not mapped, though its text reads as shader code (a note says
  // which `extensions` entry to add); `more` is how many other files of the same folder's
  // configuration share the extension.
  struct Unmapped {
    std::string extension, language, words;
    size_t more = 0;
  };
  std::optional<Unmapped> unmapped;
};

// A file a walked folder holds that is not linted, and why.
struct SkippedFile {
  std::string display;
  std::string why;
};

// Expands the command-line paths: folders recurse (sorted, following symlinks but never into a
// folder already being walked), shader extensions only (the config's "extensions"), config
// excludes applied; what a folder holds and is not linted goes to `skipped`, when given. Files
// named explicitly are always linted. The result is sorted by display path.
std::vector<InputFile> discover(const std::vector<std::string>& args, ConfigFinder& configs,
                                std::vector<SkippedFile>* skipped = nullptr);

struct ReadResult {
  std::string text;
  std::string error;          // set when the file could not be read
  size_t size = 0;
  bool too_large = false;     // larger than the limit: not read
};
ReadResult read_file(const std::filesystem::path& path, size_t max_bytes);
// Why `path` cannot be read, for a message: a dangling symbolic link says so and where it points;
// otherwise `error` as it is.
std::string unreadable_because(const std::filesystem::path& path, const std::string& error);


}  // namespace lwc

namespace lwc {

// Replaces a file's content, refusing (with a reason, nothing written) a file marked read-only,
// one with other hard links unless `split_links`, one open in another program, or one whose
// content is no longer `expected`. Where the kernel gives this process a write lease (the file's
// owner, a local file system) the file is rewritten in place under it: no other program has it
// open, whoever opens it meanwhile waits and then finds the new text whole, and the old text waits
// beside it until the new one is on disk. Elsewhere (and for `split_links`: the rename gives this
// name the new content and leaves the others the old) a temporary file beside it, given the file's
// mode, owner (where permitted) and extended attributes, is synced and swapped with it, and the
// old content checked once more at that instant. A symlink is followed and its target changed.
// Returns "" on success, else the reason.
std::string replace_file(const std::filesystem::path& path, std::string_view expected, std::string_view text, bool split_links = false);
// Creates a file that does not exist yet, atomically (temporary file, then link), with the
// umask's mode. Refuses, with a reason, if it exists. Returns "" on success, else the reason.
std::string create_file(const std::filesystem::path& path, std::string_view text);
// Makes SIGINT, SIGTERM and SIGHUP remove the temporary files being written before the process
// ends as the signal says.
void remove_temporary_files_on_signals();
// Worker threads block those signals, so the handler runs on the main thread and never inside
// the creation of a temporary file.
void block_interrupts_in_this_thread();

}  // namespace lwc
