#include "atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <utility>

#include "ccal/core/errors.hpp"

namespace ccal::cli {
namespace {

namespace fs = std::filesystem;

// --- The temporaries a signal must remove: fixed storage, so that the handler only reads memory and calls
// unlink(2), both async-signal-safe.
constexpr int kSlots = 16;
constexpr std::size_t kPathCapacity = 4096;
char g_temporary[kSlots][kPathCapacity];
volatile std::sig_atomic_t g_in_use[kSlots];
// The folders a command made for its files (OutputFolder), removed after them if they are still empty: the
// innermost one's path, and how many levels of it were made (`a/b/c` made in an empty folder: 3).
char g_folder[kPathCapacity];
volatile std::sig_atomic_t g_folder_in_use;
volatile std::sig_atomic_t g_folder_levels;

// Removes the innermost folder and then each folder made above it, innermost first; stops at the first that
// is not empty (rmdir fails), so that nothing the command did not make is removed. Cuts `path` as it goes
// (async-signal-safe: rmdir(2) and memory only).
void remove_made_folders(char* path, int levels) {
  for (int level = 0; level < levels; ++level) {
    if (::rmdir(path) != 0) return;
    char* cut = std::strrchr(path, '/');
    if (cut == nullptr || cut == path) return;
    *cut = '\0';
  }
}

extern "C" void remove_temporaries_and_end(int signal_number) {
  for (int k = 0; k < kSlots; ++k)
    if (g_in_use[k]) ::unlink(g_temporary[k]);
  if (g_folder_in_use) remove_made_folders(g_folder, g_folder_levels);  // leaves what is not empty
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigaction(signal_number, &default_action, nullptr);
  ::raise(signal_number);  // end as the signal would have, exit status included
}

// Blocks SIGINT and SIGTERM while the registry changes, so that the handler never sees half a path.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    ::sigprocmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsBlocked() { ::sigprocmask(SIG_SETMASK, &old_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t old_;
};

void install_handlers_once() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  for (int s : {SIGINT, SIGTERM}) {
    struct sigaction current {};
    ::sigaction(s, nullptr, &current);
    if (current.sa_handler == SIG_IGN) continue;  // e.g. started in the background by a shell: keep ignoring
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_end;
    sigemptyset(&action.sa_mask);
    ::sigaction(s, &action, nullptr);
  }
}

// A registered temporary file; removed (and unregistered) on destruction unless released by a rename.
class Temporary {
 public:
  Temporary() = default;
  Temporary(const Temporary&) = delete;
  Temporary& operator=(const Temporary&) = delete;
  ~Temporary() { discard(); }

  // Reserves a slot for `path` (InputError if all are taken or the path is too long).
  void adopt(const std::string& path) {
    install_handlers_once();
    SignalsBlocked blocked;
    if (path.size() >= kPathCapacity) throw InputError(fmt::format("'{}': the path is too long", path));
    for (int k = 0; k < kSlots; ++k)
      if (!g_in_use[k]) {
        std::memcpy(g_temporary[k], path.c_str(), path.size() + 1);
        g_in_use[k] = 1;
        slot_ = k;
        path_ = path;
        return;
      }
    throw InputError("too many output files at once");
  }
  // Renames the temporary over `target`; false (errno set) on failure.
  bool rename_to(const std::string& target) {
    SignalsBlocked blocked;
    if (::rename(path_.c_str(), target.c_str()) != 0) return false;
    g_in_use[slot_] = 0;
    slot_ = -1;
    return true;
  }
  void discard() {
    if (slot_ < 0) return;
    SignalsBlocked blocked;
    ::unlink(path_.c_str());
    g_in_use[slot_] = 0;
    slot_ = -1;
  }

 private:
  int slot_ = -1;
  std::string path_;
};

// --- Inputs of the command: the path of each file read, with its (device, inode) when it existed then (a
// store the command makes, e.g. the history's, is an input not there yet).
struct InputFile {
  std::string path;
  std::optional<std::pair<dev_t, ino_t>> identity;
};
std::vector<InputFile>& inputs() {
  static std::vector<InputFile> files;
  return files;
}

[[noreturn]] void fail(const FileToWrite& f, std::string_view why) {
  throw InputError(fmt::format("{}: cannot write '{}': {}", f.option, f.path, why));
}

constexpr std::string_view kStandardOutputAccepted =
    "a standard output that takes the text (a file, a terminal, or a pipe that is read)";

// The system's reason for a failed write, with what would be accepted: by the reason where it says more than
// `accepted` (what the caller's step needs).
std::string errno_text(std::string_view accepted = "a writable file in a writable folder") {
  const int e = errno;
  std::string text = std::strerror(e);
  if (e == EFBIG)
    return text + " (beyond the file-size limit, ulimit -f); accepted: a smaller output or a higher limit";
  if (e == ENOSPC || e == EDQUOT)
    return text + "; accepted: a path on a device with space for the output (or free some space)";
  if (e == EROFS) return text + "; accepted: a path on a file system mounted for writing";
  return text + "; accepted: " + std::string(accepted);
}

// Past the file-size limit (ulimit -f) write(2) raises SIGXFSZ, whose default action ends the process with
// the temporaries left behind; ignored, the write fails with EFBIG instead and the error path removes them.
void ignore_file_size_signal() {
  struct sigaction current {};
  ::sigaction(SIGXFSZ, nullptr, &current);
  if (current.sa_handler != SIG_DFL) return;  // a handler of the embedding program stays
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGXFSZ, &ignore, nullptr);
}

// What identifies an output file: (device, inode) of an existing file, else the absolute path with ".", ".."
// and symbolic links of its existing part resolved, so that "./x.txt" and "x.txt" are one file.
struct FileKey {
  std::optional<std::pair<dev_t, ino_t>> identity;
  std::string path;
  bool operator==(const FileKey&) const = default;
};

FileKey file_key(const std::string& path) {
  FileKey key;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    key.identity = std::make_pair(st.st_dev, st.st_ino);
    return key;
  }
  std::error_code ec;
  const fs::path full = fs::weakly_canonical(fs::absolute(path, ec), ec);
  key.path = ec ? path : full.lexically_normal().string();
  return key;
}

// Whether the output f names one of the command's inputs: the same file now, or the same path.
bool is_input(const FileToWrite& f, const std::optional<std::pair<dev_t, ino_t>>& identity) {
  for (const InputFile& in : inputs())
    if ((identity && in.identity == identity) || same_file(f.path, in.path)) return true;
  return false;
}

// A new file's folder: InputError unless it exists and is a folder.
void check_folder_of_new_file(const FileToWrite& f) {
  const fs::path folder = fs::path(f.path).parent_path();
  if (folder.empty()) return;
  struct stat st {};
  if (::stat(folder.c_str(), &st) != 0)
    fail(f, fmt::format("its folder '{}' does not exist; accepted: a file in an existing folder",
                        folder.string()));
  if (!S_ISDIR(st.st_mode))
    fail(f, fmt::format("'{}' is not a folder; accepted: a file in an existing folder", folder.string()));
}

bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    text.remove_prefix(std::size_t(n));
  }
  return true;
}

// The file's content to fd: its text, or what its producer writes.
bool write_content(int fd, const FileToWrite& f) {
  if (!f.produce) return write_all(fd, f.text);
  return f.produce([fd](std::string_view block) { return write_all(fd, block); });
}

// How a file is written: replaced through a temporary, or written through (device, FIFO, standard output).
struct Plan {
  enum class Kind { replace, through, standard_output } kind = Kind::replace;
  std::string target;          // the file actually replaced (a symbolic link followed)
  std::optional<mode_t> mode;  // the existing file's permissions
  std::optional<std::pair<uid_t, gid_t>> owner;
  std::optional<std::pair<dev_t, ino_t>> identity;
};

Plan plan_for(const FileToWrite& f) {
  Plan p;
  if (f.path.empty()) fail(f, "the path is empty; accepted: a file path or '-' (standard output)");
  if (f.path == "-") {
    p.kind = Plan::Kind::standard_output;
    return p;
  }
  p.target = f.path;
  struct stat st {};
  const bool exists = ::stat(f.path.c_str(), &st) == 0;  // follows symbolic links
  const int stat_error = errno;
  if (exists) p.identity = std::make_pair(st.st_dev, st.st_ino);
  // A character device (/dev/null given for an input too) is written through and loses nothing.
  if (is_input(f, p.identity) && !(exists && S_ISCHR(st.st_mode)))
    fail(f, "it is also an input of the command; accepted: a file the command does not read");
  if (!exists) {
    errno = stat_error;
    if (errno != ENOENT && errno != ENOTDIR) fail(f, errno_text());
    struct stat link {};
    if (::lstat(f.path.c_str(), &link) == 0 && S_ISLNK(link.st_mode))
      fail(f, "it is a symbolic link to nothing; accepted: a link to a file, or a file path");
    check_folder_of_new_file(f);
    return p;  // a new regular file
  }
  if (S_ISDIR(st.st_mode)) fail(f, "it is a folder; accepted: a file path");
  if (!S_ISREG(st.st_mode)) {
    p.kind =
        Plan::Kind::through;  // character or block device, FIFO, socket (also through a link: /dev/stdout)
    return p;
  }
  p.mode = st.st_mode & 07777;
  p.owner = std::make_pair(st.st_uid, st.st_gid);
  struct stat link {};
  if (::lstat(f.path.c_str(), &link) == 0 && S_ISLNK(link.st_mode)) {  // replace the file, keep the link
    std::error_code ec;
    const fs::path resolved = fs::canonical(f.path, ec);
    if (ec) fail(f, ec.message());
    p.target = resolved.string();
  }
  return p;
}

std::string random_name() {
  std::array<unsigned char, 12> bytes{};
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw InputError(std::string("cannot draw a random file name: ") + errno_text("a system with getrandom"));
    got += std::size_t(n);
  }
  std::string name = ".ccal-";
  for (unsigned char b : bytes) name += fmt::format("{:02x}", b);
  return name + ".tmp";
}

mode_t new_file_mode() {
  const mode_t mask = ::umask(022);
  ::umask(mask);
  return 0666 & ~mask;
}

// Writes f.text to a new temporary next to p.target; the temporary is registered for removal on a signal.
void write_temporary(const FileToWrite& f, const Plan& p, Temporary& temporary) {
  const fs::path folder = fs::path(p.target).parent_path();
  int fd = -1;
  std::string path;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    path = (folder.empty() ? fs::path(random_name()) : folder / random_name()).string();
    {
      SignalsBlocked blocked;  // created and registered as one step
      fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
      if (fd >= 0) temporary.adopt(path);
    }
    if (fd < 0 && errno != EEXIST) fail(f, errno_text("a file in a writable folder"));
  }
  if (fd < 0) fail(f, "no temporary file could be created in its folder");
  if (p.owner) {
    if (::fchown(fd, p.owner->first, p.owner->second) != 0) {
      // Only root may give a file away; an ordinary user's replacement is then owned by that user.
    }
  }
  const bool ok = ::fchmod(fd, p.mode ? *p.mode : new_file_mode()) == 0 && write_content(fd, f);
  const int saved = errno;
  if (::close(fd) != 0 || !ok) {
    errno = ok ? errno : saved;
    const std::string why = errno_text();
    temporary.discard();
    fail(f, why);
  }
}

void write_through(const FileToWrite& f, const Plan& p) {
  const int fd = ::open(p.target.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) fail(f, errno_text());
  const bool ok = write_content(fd, f);
  const int saved = errno;
  if (::close(fd) != 0 || !ok) {
    if (!ok) errno = saved;
    fail(f, errno_text());
  }
}

}  // namespace

void note_input_file(const std::string& path) {
  if (path.empty() || path == "-") return;
  InputFile in{path, std::nullopt};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) in.identity = std::make_pair(st.st_dev, st.st_ino);
  inputs().push_back(std::move(in));
}

void write_standard_output(const std::string& text) {
  std::cout.flush();
  if (!write_all(STDOUT_FILENO, text) || !std::cout)
    throw InputError("standard output: write failed: " + errno_text(kStandardOutputAccepted));
}

bool same_file(const std::string& a, const std::string& b) {
  if (a == b) return true;
  if (a.empty() || b.empty() || a == "-" || b == "-") return false;
  return file_key(a) == file_key(b);
}

namespace {

// How each file will be written, after every check that needs no writing (InputError naming the option).
std::vector<Plan> plans_for(const std::vector<FileToWrite>& files) {
  std::vector<Plan> plans;
  for (const auto& f : files) plans.push_back(plan_for(f));
  for (std::size_t a = 0; a < files.size(); ++a)
    for (std::size_t b = 0; b < a; ++b) {
      if (same_file(files[a].path, files[b].path))
        fail(files[a], fmt::format("it is also the {} file; accepted: two different files", files[b].option));
    }
  return plans;
}

}  // namespace

void check_files(const std::vector<FileToWrite>& files) { plans_for(files); }

OutputFolder::OutputFolder(const std::string& option, const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return;
  // The path without "." and "..", nor a closing slash: each folder made is then a prefix of it.
  std::string innermost = fs::path(path).lexically_normal().string();
  while (innermost.size() > 1 && innermost.back() == '/') innermost.pop_back();
  if (innermost.size() >= kPathCapacity)
    throw InputError(fmt::format("{}: '{}': the path is too long", option, path));
  int levels = 0;  // the folders that are missing, counted up to the first that exists
  for (fs::path p = innermost; !p.empty() && !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) {
    ++levels;
    if (p == p.parent_path()) break;
  }
  install_handlers_once();
  {
    SignalsBlocked blocked;
    std::memcpy(g_folder, innermost.c_str(), innermost.size() + 1);
    g_folder_levels = levels;
    g_folder_in_use = 1;
  }
  made_ = true;
  path_ = innermost;
  levels_ = levels;
  if (!fs::create_directories(path, ec) && !fs::is_directory(path)) {
    release();
    throw InputError(fmt::format("{}: cannot create the folder '{}': {}; accepted: a folder that exists or can "
                                 "be made there",
                                 option, path, ec ? ec.message() : std::string("a file of that name is there")));
  }
}

OutputFolder::~OutputFolder() {
  if (!made_) return;
  std::string path = path_;  // fails, leaving them, unless the write was refused before any file went in
  remove_made_folders(path.data(), levels_);
  release();
}

void OutputFolder::keep() { release(); }

void OutputFolder::release() {
  if (!made_) return;
  SignalsBlocked blocked;
  g_folder_in_use = 0;
  made_ = false;
}

void write_files(const std::vector<FileToWrite>& files) {
  ignore_file_size_signal();
  const std::vector<Plan> plans = plans_for(files);
  std::vector<Temporary> temporaries(files.size());
  for (std::size_t k = 0; k < files.size(); ++k)
    if (plans[k].kind == Plan::Kind::replace) write_temporary(files[k], plans[k], temporaries[k]);
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (plans[k].kind == Plan::Kind::through) write_through(files[k], plans[k]);
    if (plans[k].kind == Plan::Kind::standard_output) {
      if (!files[k].produce) {
        write_standard_output(files[k].text);
      } else {
        std::cout.flush();
        if (!write_content(STDOUT_FILENO, files[k]))
          throw InputError("standard output: write failed: " + errno_text(kStandardOutputAccepted));
      }
    }
  }
  for (std::size_t k = 0; k < files.size(); ++k)
    if (plans[k].kind == Plan::Kind::replace && !temporaries[k].rename_to(plans[k].target))
      fail(files[k], errno_text());
  // Every file written is named, as given, once all of them are in place; standard output, a device or a
  // FIFO is not a file the user looks for afterwards.
  for (std::size_t k = 0; k < files.size(); ++k)
    if (plans[k].kind == Plan::Kind::replace) {
      struct stat st {};
      const std::string size =
          ::stat(plans[k].target.c_str(), &st) == 0 ? fmt::format(" ({} bytes)", st.st_size) : std::string();
      std::cerr << fmt::format("ccal: wrote {}{}\n", files[k].path, size);
    }
}

}  // namespace ccal::cli
