#pragma once
// Writing a command's output files safely: atomic replacement of regular files through exclusively created
// temporaries, write-through for devices and FIFOs, and removal of the temporaries on SIGINT / SIGTERM.

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace ccal::cli {

// Writes a file's content block by block through the given writer (which returns false on a write error);
// returns false if a write failed.
using ContentProducer = std::function<bool(const std::function<bool(std::string_view)>& write)>;

// One file to write; `option` names it in messages (e.g. "-o"). Its content is `text`, or, when `produce` is
// set, what produce writes (a large file that is never all in memory).
struct FileToWrite {
  std::string option;
  std::string path;
  std::string text;
  ContentProducer produce = {};
};

// Records a file the command reads (also one it makes, such as a new history store); write_files refuses to
// write over it, by its path and, when it exists at the call, by its (device, inode).
void note_input_file(const std::string& path);

// Whether two paths name one file: the same spelling, the same (device, inode) for existing files, or the
// same absolute path with ".", ".." and links resolved for new ones ("./x.txt" and "x.txt"). "-" (standard
// output) is the same only as "-".
bool same_file(const std::string& a, const std::string& b);

// Writes every file, all or nothing as far as the file system allows: regular files are written to
// temporaries first, devices and FIFOs then, and the temporaries renamed over their targets last. Throws
// InputError naming the option and the file on any failure, with no temporary left behind (also past the
// file-size limit: SIGXFSZ is ignored, so that the write fails with EFBIG).
void write_files(const std::vector<FileToWrite>& files);

// The checks of write_files that need no writing, for a command that must know before it changes anything
// else (e.g. records a calibration) that its outputs can be written: an empty path, a file that is also an
// input or another of the files, a folder, a symbolic link to nothing, a new file whose folder does not
// exist. Throws InputError as write_files would; writes nothing.
void check_files(const std::vector<FileToWrite>& files);

// The folder a command's files go into (e.g. `simulate --logs-out`), made when it is missing (InputError
// naming the option if it cannot be, with every missing folder above it). The folders it made are removed
// again if the command ends without keep(): refused (an exception) or interrupted (SIGINT, SIGTERM) before
// any file went in, so that no empty folder is left behind, and no folder it did not make is removed. One at
// a time.
class OutputFolder {
 public:
  OutputFolder(const std::string& option, const std::string& path);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  void keep();  // the files are written: the folder stays

 private:
  void release();
  bool made_ = false;
  std::string path_;  // the innermost folder, and how many folders were made to reach it
  int levels_ = 0;
};

// Writes text to standard output and flushes it; InputError if the stream reports a write error.
void write_standard_output(const std::string& text);

}  // namespace ccal::cli
