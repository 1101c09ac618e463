// Where the shipped data files are: the folders are tried in GetDEMEDataFile's documented order.
// The engine is a static library, so "beside the binary" means beside whatever links it: the
// Python extension module (deme/_deme*.so, with deme/data next to it) or a program.
#include <deme/DataFiles.h>

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include <deme/Error.h>

namespace fs = std::filesystem;

namespace deme {

namespace {

// The file (shared object or executable) this function was loaded from.
fs::path binaryHoldingTheEngine() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&binaryHoldingTheEngine), &info) && info.dli_fname && *info.dli_fname) {
        fs::path p(info.dli_fname);
        // The main program may be reported by the name it was started with; /proc knows its path.
        if (p.is_absolute()) return p;
    }
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe;
}

}  // namespace

std::vector<std::string> GetDEMEDataDirs() {
    std::vector<std::string> dirs;
    if (const char* env = std::getenv("DEME_DATA_DIR"); env && *env) dirs.push_back(env);
    const fs::path bin = binaryHoldingTheEngine();
    if (!bin.empty()) {
        dirs.push_back((bin.parent_path() / "data").string());
        dirs.push_back((bin.parent_path().parent_path() / "share" / "deme" / "data").string());
    }
#ifdef DEME_INSTALL_DATA_DIR
    dirs.push_back(DEME_INSTALL_DATA_DIR);
#endif
#ifdef DEME_SOURCE_DATA_DIR
    dirs.push_back(DEME_SOURCE_DATA_DIR);
#endif
    return dirs;
}

std::string GetDEMEDataFile(const std::string& relative) {
    const char* call = "GetDEMEDataFile";
    if (relative.empty()) throwError(call, "the file name is empty");
    if (fs::path(relative).is_absolute())
        throwError(call, "\"" + relative + "\" is an absolute path; give a path inside the data folder");
    std::string searched;
    for (const std::string& dir : GetDEMEDataDirs()) {
        std::error_code ec;
        const fs::path candidate = fs::path(dir) / relative;
        if (fs::is_regular_file(candidate, ec)) return fs::absolute(candidate, ec).lexically_normal().string();
        searched += (searched.empty() ? "" : ", ") + dir;
    }
    throwError(call, "no data file \"" + relative + "\" in " + searched +
                         " (set DEME_DATA_DIR to a folder that holds it)");
}

}  // namespace deme
