// How ccal writes its output files: regular files replaced atomically with their permissions kept, symbolic
// links followed, devices and FIFOs written through (never replaced), inputs never overwritten, two files
// all or nothing, temporaries removed on SIGTERM, and write errors (also on standard output) exit code 2.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <chrono>
#include <cstdlib>
#include <set>
#include <string>
#include <thread>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

class OutputFiles : public Cli {
 protected:
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.insert(e.path().filename().string());
    return names;
  }
  static int exit_code_of(const std::string& shell) {
    const int status = std::system(shell.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string in_dir(const std::string& shell) const { return "cd " + quote(dir_.string()) + " && " + shell; }
};

TEST_F(OutputFiles, ARegularFileIsReplacedWithItsPermissionsKept) {
  write("out.txt", "old\n");
  fs::permissions(dir_ / "out.txt", fs::perms::owner_read | fs::perms::owner_write);
  const Result r = run("budget -o out.txt");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(read(dir_ / "out.txt").find("K3"), std::string::npos);
  EXPECT_EQ(fs::status(dir_ / "out.txt").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);  // 0600 stays 0600
  EXPECT_EQ(listing(), (std::set<std::string>{"out.txt"}));   // no temporary left
}

TEST_F(OutputFiles, ASymbolicLinkIsFollowedAndKept) {
  write("real.txt", "old\n");
  fs::create_symlink("real.txt", dir_ / "link.txt");
  ASSERT_EQ(run("budget -o link.txt").code, 0);
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.txt"));
  EXPECT_NE(read(dir_ / "real.txt").find("K3"), std::string::npos);
}

TEST_F(OutputFiles, AFifoIsWrittenThroughNotReplaced) {
  ASSERT_EQ(::mkfifo((dir_ / "pipe").c_str(), 0600), 0);
  const int code =
      exit_code_of(in_dir("(cat pipe > got.txt 2>/dev/null &) ; " + quote(kProgram) + " budget -o pipe"));
  EXPECT_EQ(code, 0);
  EXPECT_TRUE(fs::is_fifo(dir_ / "pipe"));  // still the FIFO, not a regular file put in its place
  for (int k = 0; k < 100 && read(dir_ / "got.txt").find("K3") == std::string::npos; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_NE(read(dir_ / "got.txt").find("K3"), std::string::npos);
}

// /dev/stdout is a link to the process's standard output, here a pipe: written through, not resolved.
TEST_F(OutputFiles, ALinkToAPipeIsWrittenThrough) {
  EXPECT_EQ(exit_code_of(in_dir(quote(kProgram) + " budget -o /dev/stdout | cat > got.txt")), 0);
  EXPECT_NE(read(dir_ / "got.txt").find("K3"), std::string::npos);
}

TEST_F(OutputFiles, AnOutputThatIsAnInputIsRefused) {
  const std::string example = read(kExample);
  write("cfg.toml", example);
  expect_bad_input(run("budget cfg.toml -o cfg.toml"), {"-o", "cfg.toml", "input"});
  fs::create_hard_link(dir_ / "cfg.toml", dir_ / "same.toml");
  expect_bad_input(run("simulate cfg.toml --observations-out same.toml"),
                   {"--observations-out", "same.toml", "input"});
  EXPECT_EQ(read(dir_ / "cfg.toml"), example);

  ASSERT_EQ(run("simulate --observations-out obs.csv").code, 0);
  const std::string csv = read(dir_ / "obs.csv");
  expect_bad_input(run("identify obs.csv -o obs.csv"), {"-o", "obs.csv", "input"});
  EXPECT_EQ(read(dir_ / "obs.csv"), csv);
}

TEST_F(OutputFiles, TwoFilesAreWrittenAllOrNothing) {
  write("out.txt", "old\n");
  fs::create_directory(dir_ / "folder");
  const auto before = listing();
  expect_bad_input(run("simulate -o out.txt --observations-out folder"), {"--observations-out", "folder"});
  EXPECT_EQ(read(dir_ / "out.txt"), "old\n");
  EXPECT_EQ(listing(), before);
}

TEST_F(OutputFiles, TemporariesAreRemovedOnSigterm) {
  write("out.txt", "old\n");
  ASSERT_EQ(::mkfifo((dir_ / "pipe").c_str(), 0600), 0);
  // With no reader, opening the FIFO blocks after the -o temporary is written; SIGTERM then ends the run.
  const std::string pid_file = (dir_ / "pid").string();
  ASSERT_EQ(
      exit_code_of(in_dir(quote(kProgram) + " simulate -o out.txt --observations-out pipe & echo $! > " +
                          quote(pid_file))),
      0);
  bool temporary_seen = false;
  for (int k = 0; k < 400 && !temporary_seen; ++k) {
    for (const auto& name : listing()) temporary_seen = temporary_seen || name.ends_with(".tmp");
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  const std::string pid = read(pid_file);
  ASSERT_EQ(exit_code_of("kill -TERM " + pid), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_TRUE(temporary_seen);
  for (const auto& name : listing()) EXPECT_FALSE(name.ends_with(".tmp")) << name;
  EXPECT_EQ(read(dir_ / "out.txt"), "old\n");
}

TEST_F(OutputFiles, WriteErrorsFailTheCommand) {
  const std::string err = (dir_ / "err.txt").string();
  EXPECT_EQ(exit_code_of(quote(kProgram) + " budget > /dev/full 2> " + quote(err)), 2);
  EXPECT_NE(read(err).find("standard output"), std::string::npos) << read(err);
  // Devices take the FIFO's path (written through); they are not named with -o here, so that a regression
  // run as root could not replace /dev/full or /dev/null with a regular file.
}

// Past the file-size limit write(2) raises SIGXFSZ, which ended the process with its temporary left behind;
// now the write fails with EFBIG: exit code 2, a message naming the file and the limit, no temporary, and the
// old file as it was. (dash's ulimit -f counts 512-byte blocks: 1 block, far below the budget's text.)
TEST_F(OutputFiles, TheFileSizeLimitFailsTheCommandAndLeavesNoTemporary) {
  write("out.txt", "old\n");
  const std::string err = (dir_ / "err.txt").string();
  const int code =
      exit_code_of(in_dir("ulimit -f 1 && " + quote(kProgram) + " budget -o out.txt 2> err.txt"));
  const std::string message = read(err);
  fs::remove(err);
  EXPECT_EQ(code, 2) << message;
  EXPECT_NE(message.find("-o: cannot write 'out.txt'"), std::string::npos) << message;
  EXPECT_NE(message.find("ulimit -f"), std::string::npos) << message;
  EXPECT_EQ(listing(), (std::set<std::string>{"out.txt"}));  // no temporary left
  EXPECT_EQ(read(dir_ / "out.txt"), "old\n");
}

// One file by two spellings was written twice (the second replacing the first); now refused by identity, and
// the -o file is written alone once the other option names a different file.
TEST_F(OutputFiles, OneFileNamedTwiceIsRefusedWhateverTheSpelling) {
  const std::string through_parent = "../" + dir_.filename().string() + "/same.txt";
  for (const std::string& path : {std::string("same.txt"), std::string(".//same.txt"), through_parent}) {
    SCOPED_TRACE(path);
    expect_bad_input(run("simulate -o ./same.txt --observations-out " + path),
                     {"--observations-out", "-o file"});
    EXPECT_TRUE(listing().empty());
  }
  ASSERT_EQ(run("simulate -o ./same.txt --observations-out obs.csv").code, 0);
  EXPECT_EQ(listing(), (std::set<std::string>{"same.txt", "obs.csv"}));
}

TEST_F(OutputFiles, ALegalLongFileNameIsAccepted) {
  const std::string name(255, 'a');  // NAME_MAX on Linux file systems
  ASSERT_EQ(run("budget -o " + name).code, 0);
  EXPECT_NE(read(dir_ / name).find("K3"), std::string::npos);
}

// An empty -o would mean standard output silently (the internal meaning of no -o); given explicitly it is a
// mistake (an unset shell variable), refused at parsing for every command with -o, before any work.
TEST_F(OutputFiles, AnEmptyOutputPathIsRefused) {
  for (const std::string& command :
       {std::string("budget"), std::string("simulate --observations-out obs.csv"),
        std::string("history show S1 --db none.sqlite"), std::string("report --trials 2000")}) {
    SCOPED_TRACE(command);
    expect_bad_input(run(command + " -o ''"),
                     {"-o: the path is empty; accepted: a file path or '-' for standard output"});
    EXPECT_TRUE(listing().empty());
  }
  ASSERT_EQ(run("budget -o -").code, 0);
  // The further outputs have no standard output: an empty path was "write nothing" with exit 0. Each is
  // refused naming its option.
  for (const auto& [command, option] :
       {std::pair<std::string, std::string>{"report --trials 2000 --pdf ''", "--pdf"},
        {"design --plan-out ''", "--plan-out"},
        {"montecarlo --trials 2000 --samples-out ''", "--samples-out"},
        {"simulate --logs-out ''", "--logs-out"},
        {"simulate --observations-out ''", "--observations-out"},
        {"identify obs.csv --statement-out ''", "--statement-out"}}) {
    SCOPED_TRACE(command);
    expect_bad_input(run(command), {option + ": the path is empty; accepted: a"});
    EXPECT_TRUE(listing().empty());
  }
}

// A new file in a folder that does not exist (or a file in place of the folder) is refused naming the folder,
// before anything is written.
TEST_F(OutputFiles, AMissingFolderIsNamed) {
  expect_bad_input(
      run("simulate --observations-out obs.csv -o nodir/out.txt"),
      {"-o: cannot write 'nodir/out.txt': its folder 'nodir' does not exist; accepted: a file in an "
       "existing folder"});
  write("plain", "x\n");
  expect_bad_input(run("budget -o plain/out.txt"), {"'plain' is not a folder"});
  EXPECT_EQ(listing(), (std::set<std::string>{"plain"}));
}

}  // namespace
}  // namespace ccal::test
