#include "ccal/render/pdf_print.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/render/pdf_info.hpp"

extern char** environ;

namespace ccal {
namespace {

namespace fs = std::filesystem;

constexpr const char* kBrowsers[] = {"chromium", "chromium-browser", "google-chrome-stable", "google-chrome"};
constexpr const char* kInstallHint =
    "accepted: a Chromium in PATH (Debian: apt-get install chromium), or its path in the environment's "
    "CCAL_CHROMIUM";

bool executable(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

// A program name as the shell finds it: a path as it is, a bare name in PATH's folders.
std::string in_path(const std::string& name) {
  if (name.find('/') != std::string::npos) return executable(name) ? name : std::string();
  const char* path = std::getenv("PATH");
  std::istringstream folders(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / name;
    if (executable(candidate)) return candidate.string();
  }
  return {};
}

// A private folder for one print, removed with everything in it when the print is over.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = (fs::path(tmp && *tmp ? tmp : "/tmp") / "ccal-pdf-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr)
      throw InputError(fmt::format("cannot make a temporary folder in {} for the browser; check TMPDIR",
                                   fs::path(pattern).parent_path().string()));
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The last lines of the browser's error stream, for a one-line message ("a | b | c").
std::string tail(const std::string& text, std::size_t lines) {
  std::vector<std::string> kept;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    kept.push_back(line);
    if (kept.size() > lines) kept.erase(kept.begin());
  }
  return kept.empty() ? "nothing" : fmt::format("{}", fmt::join(kept, " | "));
}

// Runs the browser in a process group of its own (so that its helpers can be stopped with it); its exit status,
// or nullopt after `timeout_s` (the group then killed).
std::optional<int> run(const std::vector<std::string>& args, const fs::path& log, double timeout_s) {
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK);
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &files, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0)
    throw InputError(fmt::format("cannot run the browser {}: {}; {}", args[0], std::strerror(spawned), kInstallHint));
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) {
      ::kill(-pid, SIGKILL);  // helpers the browser left behind
      return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    if (done < 0 && errno != EINTR) return 127;
    if (std::chrono::steady_clock::now() > end) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      return std::nullopt;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

std::string find_pdf_browser(const PdfPrintOptions& options) {
  if (!options.browser.empty()) return in_path(options.browser);
  if (const char* named = std::getenv("CCAL_CHROMIUM"); named && *named) return in_path(named);
  for (const char* name : kBrowsers)
    if (std::string found = in_path(name); !found.empty()) return found;
  return {};
}

std::string require_pdf_browser(const PdfPrintOptions& options) {
  std::string browser = find_pdf_browser(options);
  if (!browser.empty()) return browser;
  const char* named = std::getenv("CCAL_CHROMIUM");
  const std::string asked = !options.browser.empty() ? options.browser : named && *named ? named : "";
  throw InputError(asked.empty() ? fmt::format("no browser to print the PDF with; {}", kInstallHint)
                                 : fmt::format("the browser '{}' is not an executable file; {}", asked,
                                               kInstallHint));
}

std::string print_pdf(std::string_view html, const PdfPrintOptions& options) {
  const std::string browser = require_pdf_browser(options);
  const TemporaryFolder folder;
  const fs::path page = folder.path() / "page.html", pdf = folder.path() / "page.pdf",
                 log = folder.path() / "browser.log";
  {
    std::ofstream out(page, std::ios::binary);
    out.write(html.data(), std::streamsize(html.size()));
    if (!out.flush())
      throw InputError(fmt::format("cannot write the page for the browser to {}; check TMPDIR", page.string()));
  }
  std::vector<std::string> args{browser, "--headless", "--disable-gpu", "--no-first-run",
                                "--no-default-browser-check", "--disable-extensions", "--disable-sync",
                                "--disable-background-networking", "--disable-crash-reporter", "--mute-audio",
                                // The page needs no network: every host name fails to resolve.
                                "--host-resolver-rules=MAP * ~NOTFOUND",
                                "--user-data-dir=" + (folder.path() / "profile").string(),
                                "--no-pdf-header-footer",
                                // Time to run the page's scripts (the charts) before printing.
                                "--virtual-time-budget=20000", "--print-to-pdf=" + pdf.string(),
                                "file://" + page.string()};
  if (::geteuid() == 0) args.insert(args.begin() + 1, "--no-sandbox");  // Chromium refuses root otherwise
  const std::optional<int> status = run(args, log, options.timeout_s);
  const std::string said = tail(read_all(log), 6);
  if (!status)
    throw InputError(fmt::format("the browser {} did not finish printing within {:g} s; it said: {}", browser,
                                 options.timeout_s, said));
  std::string bytes = read_all(pdf);
  if (*status != 0 || !bytes.starts_with("%PDF-"))
    throw InputError(fmt::format("the browser {} wrote no PDF (exit status {}); it said: {}", browser, *status,
                                 said));
  // The browser sets the title only: the page's author, subject, generator and date are set after it.
  return with_pdf_info(std::move(bytes), pdf_info_of_page(html));
}

}  // namespace ccal
