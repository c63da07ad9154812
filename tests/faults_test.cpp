// Faults that must lose nothing (issue "Reliability"): an output folder that refuses writes, a
// full disk, Ctrl-C or SIGTERM in the middle of the work, two processes sharing one reference
// cache. Each command exits 4 (or 128 + the signal) naming what went wrong, and leaves no
// temporary file and no half report behind.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli_harness.h"

// Everything of this file in its own namespace: e2e_tests is a unity build.
namespace twinrender::e2e::faults_test {

namespace tt = twinrender::test;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

const std::string SLAB = ::twinrender::testing::sourceDir().string() + "/tests/scenes/slab.toml";
// A tiny frame: these tests are about files, not pictures.
const std::string TINY = " --set camera.width=48 --set camera.height=32";

// The files a command must not leave behind: temporary names (written beside their target
// with a leading dot: core/image_io.h, app/output_folder.h, app/reference_cache.cpp).
std::vector<std::string> temporaryFiles(const fs::path& dir) {
    std::vector<std::string> found;
    if (!fs::exists(dir)) return found;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string().front() == '.') found.push_back(e.path().string());
    return found;
}

// The report files of `run` under `dir` (docs/design.md): all of them or none may be there.
const std::vector<std::string> RUN_REPORT = {"summary.json", "summary.md", "index.html",
                                             "slab/metrics.json", "slab/index.html"};

std::size_t reportFilesIn(const fs::path& dir, const std::vector<std::string>& report) {
    std::size_t n = 0;
    for (const auto& f : report) n += fs::exists(dir / f);
    return n;
}

// Whether this process may write into a folder of mode 0500 anyway (root, with
// CAP_DAC_OVERRIDE): the commands then run with that capability dropped (setpriv), as an
// ordinary user would.
std::string withoutOverride() {
    if (geteuid() != 0) return "";
    return "setpriv --bounding-set=-dac_override,-dac_read_search --inh-caps=-all ";
}

// The commands that write, each with `out` as its output folder; `inputs` holds what they
// read (two renders for compare, a shard for merge), made beforehand.
std::vector<std::pair<std::string, std::string>> writingCommands(const fs::path& inputs,
                                                                 const fs::path& out) {
    const std::string o = " --out " + out.string();
    return {
        {"render", "render " + SLAB + " --renderer raymarch" + TINY + o},
        {"run", "run " + SLAB + TINY + o},
        {"compare", "compare " + (inputs / "slab/raymarch.exr").string() + " " +
                        (inputs / "slab/realtime.exr").string() + o},
        {"sweep",
         "sweep " + SLAB + " --vary realtime.ssss.enabled=true,false --frames 1" + TINY + o},
        {"study", "study depth_range --quick --set camera.width=48 --set camera.height=32" + o},
        {"merge", "merge " + (inputs / "shard").string() + o},
    };
}

// Renders and a shard that `compare` and `merge` read.
fs::path makeInputs(const std::string& name) {
    const fs::path dir = tt::freshDir(name);
    const auto r =
        tt::runTwinrender("render " + SLAB + " --renderer both" + TINY + " --out " + dir.string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    const auto s =
        tt::runTwinrender("run " + SLAB + TINY + " --shard 1/1 --out " + (dir / "shard").string());
    EXPECT_LE(s.exitCode, 2) << s.output;
    return dir;
}

}  // namespace

// A folder that refuses writes (mode 0500): every command that writes says so before it
// renders anything, exit 4 naming the folder, and the folder stays empty.
TEST(Faults, UnwritableOutputFolderIsExit4NamingItAndLeavesNothing) {
    const fs::path inputs = makeInputs("faults_unwritable_inputs");
    const fs::path base = tt::freshDir("faults_unwritable");
    for (const auto& [name, _] : writingCommands(inputs, base)) {
        const fs::path out = base / name;
        fs::create_directories(out);
        fs::permissions(out, fs::perms::owner_read | fs::perms::owner_exec);
        std::string command;
        for (const auto& [n, args] : writingCommands(inputs, out))
            if (n == name) command = args;
        const auto r = tt::runTwinrender(command, "", withoutOverride());
        fs::permissions(out, fs::perms::owner_all);
        EXPECT_EQ(r.exitCode, 4) << name << ": " << r.output;
        EXPECT_NE(r.output.find(out.string()), std::string::npos) << name << ": " << r.output;
        EXPECT_NE(r.output.find("Permission denied"), std::string::npos)
            << name << ": " << r.output;
        EXPECT_EQ(tt::countFiles(out), 0u) << name;
    }
}

namespace {

// A file system of `kib` KiB at `dir` that this test process alone sees (a tmpfs in a mount
// namespace of its own, gone when the process ends); false where that cannot be made (not
// root, or no CAP_SYS_ADMIN), and the caller limits the file size instead.
bool mountSmallFileSystem(const fs::path& dir, int kib) {
    static bool ownNamespace = geteuid() == 0 && unshare(CLONE_NEWNS) == 0 &&
                               mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) == 0;
    if (!ownNamespace) return false;
    umount(dir.c_str());
    fs::create_directories(dir);
    const std::string options = "size=" + std::to_string(kib) + "k";
    return mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
}

}  // namespace

// A disk that fills up part way through: whatever was written when the disk filled, the
// command exits 4 naming the file and the reason, leaves no temporary file, and its report is
// all there or not at all. Each size fills at another file (the renders, the error maps, the
// report). Where no size-limited file system can be mounted, a file size limit
// (RLIMIT_FSIZE, with SIGXFSZ ignored so that the write fails with EFBIG) stands in for it.
TEST(Faults, FullDiskIsExit4NamingTheFileWithNoTemporaryFileAndNoHalfReport) {
    const fs::path inputs = makeInputs("faults_full_inputs");
    const fs::path base = tt::freshDir("faults_full");
    int failures = 0;
    for (int kib : {8, 48, 160}) {
        const fs::path disk = base / ("disk" + std::to_string(kib));
        const bool mounted = mountSmallFileSystem(disk, kib);
        fs::create_directories(disk);
        const std::string limit = mounted ? ""
                                          : "sh -c 'trap \"\" XFSZ; ulimit -f " +
                                                std::to_string(kib / 8) + "; exec \"$0\" \"$@\"' ";
        for (const auto& [name, args] : writingCommands(inputs, disk / "out")) {
            if (name == "study") continue;  // its renders are the run's; a second is minutes
            fs::remove_all(disk / "out");
            const auto r = tt::runTwinrender(args, "", limit);
            const std::string what = name + " on " + std::to_string(kib) + " KiB: ";
            EXPECT_TRUE(r.exitCode == 4 || r.exitCode <= 2) << what << r.output;
            if (r.exitCode == 4) {
                ++failures;
                EXPECT_NE(r.output.find((disk / "out").string()), std::string::npos)
                    << what << r.output;
                EXPECT_NE(r.output.find("disk not full"), std::string::npos) << what << r.output;
            }
            EXPECT_EQ(temporaryFiles(disk), std::vector<std::string>{}) << what << r.output;
            if (name == "run" || name == "merge") {
                const std::size_t n = reportFilesIn(disk / "out", RUN_REPORT);
                EXPECT_TRUE(n == 0 || n == RUN_REPORT.size()) << what << n << " report files";
            }
            if (name == "sweep") {
                const std::size_t n = reportFilesIn(
                    disk / "out", {"sweep.json", "sweep.csv", "sweep.svg", "index.html"});
                EXPECT_TRUE(n == 0 || n == 4) << what << n << " report files";
            }
        }
        if (mounted) umount(disk.c_str());
    }
    EXPECT_GT(failures, 0) << "no size was small enough to fill";
}

// A twinrender process started with SIGINT and SIGTERM at their default action (a background
// job of a non-interactive shell ignores SIGINT, and a child inherits that: PLATFORM.md).
struct Child {
    pid_t pid = -1;
    fs::path log;
};

Child start(const std::vector<std::string>& args, const fs::path& log) {
    Child c;
    c.log = log;
    const std::string program = ::twinrender::testing::twinrenderProgram();  // before the fork
    c.pid = fork();
    if (c.pid == 0) {
        signal(SIGINT, SIG_DFL);
        signal(SIGTERM, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, nullptr);
        const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(fd, STDOUT_FILENO);
        dup2(fd, STDERR_FILENO);
        std::vector<char*> argv;
        argv.push_back(const_cast<char*>(program.c_str()));
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(program.c_str(), argv.data());
        _exit(127);
    }
    return c;
}

// The exit status (or 128 + the signal that ended it).
int wait(const Child& c) {
    int status = 0;
    waitpid(c.pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Waits (up to a minute) until process `pid` catches `signal` (SigCgt in /proc/PID/status).
bool waitForHandler(pid_t pid, int signal) {
    const auto until = Clock::now() + std::chrono::minutes(1);
    while (Clock::now() < until) {
        std::ifstream in("/proc/" + std::to_string(pid) + "/status");
        std::string line;
        while (std::getline(in, line))
            if (line.rfind("SigCgt:", 0) == 0 &&
                (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1)
                return true;
        if (waitpid(pid, nullptr, WNOHANG) != 0) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
}

std::vector<std::string> split(const std::string& args) {
    std::vector<std::string> out;
    std::size_t at = 0;
    while (at < args.size()) {
        const std::size_t end = std::min(args.find(' ', at), args.size());
        if (end > at) out.push_back(args.substr(at, end - at));
        at = end + 1;
    }
    return out;
}

struct Interruption {
    const char* command;
    int signal;
};

// How the test's parameter shows in its CTest name.
void PrintTo(const Interruption& p, std::ostream* os) {
    *os << p.command << " SIG" << sigabbrev_np(p.signal);
}

class InterruptTest : public ::testing::TestWithParam<Interruption> {};

// A signal in the middle of the reference render: the process stops within about a second
// (the raymarcher polls the flag between tiles of milliseconds), exits with 128 + the signal,
// and leaves no temporary file and no report.
TEST_P(InterruptTest, StopsPromptlyWith128PlusTheSignalAndLeavesNoReport) {
    const Interruption p = GetParam();
    const fs::path dir = tt::freshDir(std::string("faults_interrupt_") + p.command);
    const fs::path out = dir / "out";
    // A render of several seconds on two cores (about 1 s of it is loading and set-up).
    const std::string heavy =
        " --set camera.width=640 --set camera.height=480 --set raymarch.spp=4";
    const std::string command = p.command;
    const std::string args =
        command == "run"     ? "run " + SLAB + heavy + " --out " + out.string()
        : command == "sweep" ? "sweep " + SLAB + heavy +
                                   " --vary realtime.ssss.enabled=true,false --out " + out.string()
                             : "study particle_size --quick" + heavy + " --out " + out.string();
    const Child c = start(split(args), dir / "log.txt");
    // Until the handlers are installed (a signal before main would end the process by its
    // default action), then a second more: the raymarcher is under way, and its render is
    // what the signal must cut short.
    ASSERT_TRUE(waitForHandler(c.pid, p.signal)) << tt::readText(c.log);
    std::this_thread::sleep_for(std::chrono::seconds(1));
    ASSERT_EQ(waitpid(c.pid, nullptr, WNOHANG), 0)
        << "ended before the signal: " << tt::readText(c.log);
    const auto sent = Clock::now();
    kill(c.pid, p.signal);
    const int code = wait(c);
    const double seconds = std::chrono::duration<double>(Clock::now() - sent).count();
    const std::string log = tt::readText(c.log);
    EXPECT_EQ(code, 128 + p.signal) << log;
    // "Within a second or so": a tile takes milliseconds; the bound leaves room for a machine
    // whose two cores other jobs share (and for the sanitizers' slowdown).
    EXPECT_LT(seconds, 3.0) << log;
    std::printf("stopped %.3f s after the signal\n", seconds);
    EXPECT_NE(log.find("stopped by SIG"), std::string::npos) << log;
    EXPECT_EQ(temporaryFiles(out), std::vector<std::string>{});
    for (const char* f : {"summary.json", "summary.md", "index.html", "slab/metrics.json",
                          "sweep.json", "sweep.csv", "studies.json", "particle_size"})
        EXPECT_FALSE(fs::exists(out / f)) << f;
}

INSTANTIATE_TEST_SUITE_P(Faults, InterruptTest,
                         ::testing::Values(Interruption{"run", SIGINT},
                                           Interruption{"sweep", SIGTERM},
                                           Interruption{"study", SIGINT}),
                         [](const auto& info) {
                             return std::string(info.param.command) +
                                    (info.param.signal == SIGINT ? "_SIGINT" : "_SIGTERM");
                         });

namespace {

// The metrics of a sweep's combination, without the times (measured anew by each process).
nlohmann::json metricsWithoutTimes(const fs::path& file) {
    nlohmann::json m = tt::readJson(file).value("metrics", nlohmann::json::object());
    for (auto it = m.begin(); it != m.end();)
        it = it.key().rfind("time.", 0) == 0 ? m.erase(it) : std::next(it);
    return m;
}

}  // namespace

// Two processes sharing one --cache folder, started together so both miss and both render the
// reference: each entry appears whole under its key (one folder renamed into place), neither
// reads the other's half-written files, no temporary folder stays, and both measure the same.
// A damaged entry is rendered anew, not read.
TEST(Faults, TwoProcessesSharingACacheFinishWithTheSameResult) {
    const fs::path dir = tt::freshDir("faults_cache_race");
    const fs::path cache = dir / "cache";
    const std::string args = "sweep " + SLAB +
                             " --vary realtime.ssss.enabled=true,false --frames 1 --set "
                             "camera.width=320 --set camera.height=240 --cache " +
                             cache.string() + " --out ";
    const Child a = start(split(args + (dir / "a").string()), dir / "a.txt");
    const Child b = start(split(args + (dir / "b").string()), dir / "b.txt");
    const int codeA = wait(a), codeB = wait(b);
    const std::string logA = tt::readText(a.log), logB = tt::readText(b.log);
    ASSERT_EQ(codeA, 0) << logA;
    ASSERT_EQ(codeB, 0) << logB;
    for (const char* c : {"combinations/c000/metrics.json", "combinations/c001/metrics.json"}) {
        const auto ma = metricsWithoutTimes(dir / "a" / c), mb = metricsWithoutTimes(dir / "b" / c);
        EXPECT_FALSE(ma.empty()) << c;
        EXPECT_EQ(ma, mb) << c;
    }
    EXPECT_EQ(temporaryFiles(cache), std::vector<std::string>{});
    std::vector<fs::path> entries;
    for (const auto& e : fs::directory_iterator(cache)) entries.push_back(e.path());
    ASSERT_EQ(entries.size(), 1u) << "one reference for both combinations";
    for (const char* f : {"raymarch.exr", "raymarch.png", "raymarch.json", "key.json"})
        EXPECT_TRUE(fs::is_regular_file(entries[0] / f)) << f;

    // A damaged entry (cut short on disk) is refused and rendered anew.
    fs::resize_file(entries[0] / "raymarch.exr", 100);
    const auto r = tt::runTwinrender(args + (dir / "c").string());
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("cached render unusable"), std::string::npos) << r.output;
    EXPECT_EQ(metricsWithoutTimes(dir / "c/combinations/c000/metrics.json"),
              metricsWithoutTimes(dir / "a/combinations/c000/metrics.json"));
    EXPECT_EQ(temporaryFiles(cache), std::vector<std::string>{});
    const auto hit = tt::runTwinrender(args + (dir / "d").string());
    EXPECT_NE(hit.output.find("cache hit"), std::string::npos) << hit.output;
}

}  // namespace twinrender::e2e::faults_test
