// `actuator serve`: an evaluation server for --workers (Cap'n Proto RPC).
#include <kj/exception.h>

#include <iostream>

#include "commands/registry.h"
#include "options/cli.h"
#include "evaluation/remote.h"

namespace app {

static int RunServe(int argc, char** argv, int first) {
    Cli cli("serve", "Runs an evaluation server: Cap'n Proto RPC, interface Evaluator in app/schema/actuator.capnp (see README). It takes batches of "
                     "designs with settings and returns results and meshes, evaluating on all its cores, until it is killed. Bad or hostile "
                     "requests get an error reply or a closed connection; the server keeps serving. Use it from sweep, evolve or reproduce with "
                     "--workers host:port,...");
    ServeOptions options;
    cli.Text("--listen", options.listen, "where to listen; a bare port means 127.0.0.1:PORT; port 0 picks a free one")->type_name("ADDRESS:PORT");
    cli.Integer("--threads", options.threads, "evaluation threads per call (0: every core)", 0, 1024);
    if (!cli.Parse(argc, argv, first)) return 0;
    options.listen = ParseListenAddress(options.listen);
    try {
        Serve(options);
    } catch (const kj::Exception& error) {
        throw UsageError("--listen " + options.listen + ": " + error.getDescription().cStr());
    }
    return 0;
}

static const RegisterCommand kServeCommand{{"serve", "run an evaluation server for --workers (Cap'n Proto RPC)", 90, RunServe}};

}  // namespace app
