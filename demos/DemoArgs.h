// Command line shared by the simple demos: [output folder] [--quick], in either order.
#pragma once

#include <cstring>
#include <filesystem>

struct DemoArgs {
    std::filesystem::path outDir;
    bool quick = false;
};

inline DemoArgs parseDemoArgs(int argc, char** argv, const char* defaultDir) {
    DemoArgs a{defaultDir, false};
    for (int i = 1; i < argc; i++) {
        if (std::strcmp(argv[i], "--quick") == 0)
            a.quick = true;
        else
            a.outDir = argv[i];
    }
    return a;
}
