// octrace options: the options table as users and tools read it. Plain: one block per setting
// (flag, key, kind, range or choices, default, session member, studio control, commands);
// --markdown: the lines docs/user/cli.md shows under the options' headings (scripts/cli_doc.py).
#include "Commands.h"
#include "Options.h"

#include "octrace/model/OptionTable.h"
#include "octrace/util/Error.h"

#include <cstdio>
#include <string>

namespace octrace::cli {

int runOptions(const std::vector<std::string>& args) {
    bool help = false, markdown = false;
    OptionParser p("options", "octrace options [--markdown]");
    p.add({"markdown", "", "print, per option with a flag, its command, its heading's start and its generated line of docs/user/cli.md, tab-separated (default: the table for people)",
           [&](const std::string&) { markdown = true; }});
    p.add({"help", "", "show this help and exit", [&](const std::string&) { help = true; }});
    if (!p.parse(args).empty()) throw UsageError("options takes no INPUT");
    if (help) {
        std::fputs(p.help().c_str(), stdout);
        return 0;
    }
    for (const model::Option* o : model::allOptions()) {
        const std::string flag = *o->flag ? std::string("--") + o->flag : std::string();
        if (markdown) {
            if (!flag.empty())
                std::printf("%s\t### %s\t%s\n", o->docCommand().c_str(), flag.c_str(), o->docLine().c_str());
            continue;
        }
        std::printf("%s\n", (flag.empty() ? o->key : flag + (*o->argument && o->kind != model::OptionKind::Flag ? std::string(" ") + o->argument : "")).c_str());
        std::printf("    key %s; %s\n", o->key, model::sayForCli(o->helpLine()).c_str());
        if (*o->session) std::printf("    session member %s\n", o->session);
        if (*o->label) std::printf("    studio control \"%s\"\n", o->label);
        if (*o->commands) std::printf("    commands: %s\n", o->commands);
    }
    return 0;
}

}  // namespace octrace::cli
