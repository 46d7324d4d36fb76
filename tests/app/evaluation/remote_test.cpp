// Evaluation servers on loopback: results equal a local run's, a server killed mid-run loses
// nothing, a run whose servers are all gone stops with exit code 3, and malformed or hostile
// messages never take a server down.
#include <arpa/inet.h>
#include <capnp/ez-rpc.h>
#include <capnp/message.h>
#include <capnp/serialize.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "cli_fixture.h"
#include "evaluation/remote.h"
#include "formats/schema_convert.h"

namespace fs = std::filesystem;

namespace {

using testing_support::Child;
using ::testing::HasSubstr;

// An `actuator serve` child process on a free loopback port, killed when the test ends.
class Server {
public:
    explicit Server(const fs::path& log) : log_(log), child_({ACTUATOR_BIN, "serve", "--listen", "127.0.0.1:0", "--threads", "1"}, log.string()) {
        testing_support::WaitUntil(
            [&] {
                std::ifstream in(log_);
                std::string word;
                while (in >> word)
                    if (word.rfind("127.0.0.1:", 0) == 0) port_ = std::stoi(word.substr(10));
                return port_ != 0;
            },
            5);
    }
    void Kill() { child_.Kill(SIGKILL); }
    bool Alive() const { return child_.Running(); }
    std::string Address() const { return "127.0.0.1:" + std::to_string(port_); }
    int Port() const { return port_; }

private:
    fs::path log_;
    Child child_;
    int port_ = 0;
};

class Remote : public CliTest {
protected:
    std::string Sweep(int points, int iterations) const {
        Write("sweep.json", R"({"id": "remote", "model": {"name": "thesis"}, "sim": {"iterations": )" + std::to_string(iterations) + R"(},
            "sweep": {"shape": {"family": "sine", "phase": [0.5, "pi-0.5"]},
                      "axes": [{"parameter": "amplitude", "from": 1, "to": 10, "points": )" + std::to_string(points) + R"(}]},
            "render": {"figures": false, "thumbnails": false}})");
        return Path("sweep.json");
    }
    std::string Ga() const {
        Write("ga.json", R"({"model": {"name": "thesis"}, "id": "remote-ga", "seed": 5, "sim": {"iterations": 2000},
            "evolve": {"runs": 1, "population": 8, "generations": 3, "genome": {"kind": "bspline", "splines": 1, "length": [5, 8]}},
            "render": {"figures": false, "thumbnails": false}})");
        return Path("ga.json");
    }
    // A raw TCP connection that sends bytes and closes: what a broken or hostile client does.
    static void SendRaw(int port, const std::string& bytes) {
        const int fd = socket(AF_INET, SOCK_STREAM, 0);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(static_cast<uint16_t>(port));
        inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
        if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
            (void)!write(fd, bytes.data(), bytes.size());
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        close(fd);
    }
};

}  // namespace

TEST_F(Remote, TwoServersGiveTheSameResultsAsALocalRun) {
    Server a(Path("a.log")), b(Path("b.log"));
    ASSERT_GT(a.Port(), 0);
    ASSERT_GT(b.Port(), 0);
    const std::string workers = " --workers " + a.Address() + "," + b.Address();
    ASSERT_EQ(Run("sweep " + Sweep(8, 3000) + " --out " + Path("local")).exitCode, 0);
    const Result remote = Run("sweep " + Sweep(8, 3000) + " --out " + Path("remote") + workers);
    ASSERT_EQ(remote.exitCode, 0) << remote.err;
    EXPECT_EQ(Slurp(dir_ / "remote" / "results.csv"), Slurp(dir_ / "local" / "results.csv"));

    ASSERT_EQ(Run("evolve " + Ga() + " --out " + Path("ga-local")).exitCode, 0);
    const Result ga = Run("evolve " + Ga() + " --out " + Path("ga-remote") + workers + ",local");
    ASSERT_EQ(ga.exitCode, 0) << ga.err;
    for (const char* file : {"logbook.csv", "halloffame.csv", "best_per_generation.csv"})
        EXPECT_EQ(Slurp(dir_ / "ga-remote" / "run_1" / file), Slurp(dir_ / "ga-local" / "run_1" / file)) << file;
    EXPECT_EQ(Slurp(dir_ / "ga-remote" / "evaluations.csv"), Slurp(dir_ / "ga-local" / "evaluations.csv"));

    // A pagmo optimizer's batches go through the same pool: NSGA-II under the shell model.
    Write("nsga2.json", R"({"id": "remote-nsga2", "seed": 5, "model": {"name": "shell", "geometry": {"ring_vertices": 12, "rings": 16, "edge_spacing_mm": 0}, "load": {"steps": 2}},
        "optimizer": {"algorithm": "nsga2", "population": 8, "generations": 2, "objectives": ["contraction", "max_stretch"],
                      "genome": {"family": "bspline", "splines": 1, "control_points": 5}},
        "render": {"figures": false, "thumbnails": false}})");
    ASSERT_EQ(Run("evolve " + Path("nsga2.json") + " --out " + Path("o-local")).exitCode, 0);
    const Result optimizer = Run("evolve " + Path("nsga2.json") + " --out " + Path("o-remote") + workers + ",local");
    ASSERT_EQ(optimizer.exitCode, 0) << optimizer.err;
    for (const char* file : {"run_1/logbook.csv", "run_1/pareto_front.csv", "evaluations.csv"})
        EXPECT_EQ(Slurp(dir_ / "o-remote" / file), Slurp(dir_ / "o-local" / file)) << file;
}

// 5,000 points against one server: more than a call may carry (the server says so in info()), so
// the pool splits the batch; the results equal the local sweep's.
TEST_F(Remote, ALargeSweepAgainstOneServerEqualsTheLocalSweep) {
    Server server(Path("s.log"));
    ASSERT_GT(server.Port(), 0);
    ASSERT_EQ(Run("sweep " + Sweep(5000, 20) + " --out " + Path("local")).exitCode, 0);
    const Result remote = Run("sweep " + Sweep(5000, 20) + " --out " + Path("remote") + " --workers " + server.Address());
    ASSERT_EQ(remote.exitCode, 0) << remote.err;
    EXPECT_EQ(Slurp(dir_ / "remote" / "results.csv"), Slurp(dir_ / "local" / "results.csv"));
    EXPECT_EQ(Slurp(dir_ / "remote" / "evaluations.csv"), Slurp(dir_ / "local" / "evaluations.csv"));
    EXPECT_TRUE(server.Alive());
}

TEST_F(Remote, AServerKilledMidRunLosesNothing) {
    Server a(Path("a.log")), b(Path("b.log"));
    ASSERT_GT(a.Port(), 0);
    ASSERT_GT(b.Port(), 0);
    ASSERT_EQ(Run("sweep " + Sweep(30, 10000) + " --out " + Path("local")).exitCode, 0);
    // Kill server a while the batch runs: once the first results are recorded, every worker has
    // calls in flight (a batch goes out as several calls per worker), whatever the machine's load.
    std::thread killer([&] {
        testing_support::WaitUntil(
            [&] {
                std::ifstream in(dir_ / "remote" / "evaluations.csv");
                std::string line;
                int lines = 0;
                while (std::getline(in, line)) ++lines;
                return lines >= 3;
            },
            30);
        a.Kill();
    });
    const Result remote = Run("sweep " + Sweep(30, 10000) + " --out " + Path("remote") + " --workers " + a.Address() + "," + b.Address());
    killer.join();
    ASSERT_EQ(remote.exitCode, 0) << remote.err;
    EXPECT_THAT(remote.err, HasSubstr("worker " + a.Address() + " failed"));
    EXPECT_THAT(remote.err, HasSubstr("shapes go to the other workers"));
    EXPECT_EQ(Slurp(dir_ / "remote" / "results.csv"), Slurp(dir_ / "local" / "results.csv"));
    EXPECT_TRUE(b.Alive());
}

TEST_F(Remote, ARunWithoutLiveServersStopsWithExitCode3) {
    Server a(Path("a.log"));
    const std::string address = a.Address();
    a.Kill();
    const Result r = Run("evolve " + Ga() + " --out " + Path("gone") + " --workers " + address);
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_THAT(r.err, HasSubstr("every worker is gone"));
    ExpectRefused("sweep " + Sweep(3, 100) + " --out " + Path("x") + " --workers ,", "--workers");
    ExpectRefused("sweep " + Sweep(3, 100) + " --out " + Path("x") + " --workers nohost", "needs a port");
    ExpectRefused("sweep " + Sweep(3, 100) + " --out " + Path("x") + " --workers 127.0.0.1:99999", "out of range");
    ExpectRefused("sweep " + Sweep(3, 100) + " --out " + Path("x") + " --worker-timeout 1e10 --workers local", "--worker-timeout");
    ExpectRefused("sweep " + Sweep(3, 100) + " --out " + Path("x") + " --worker-timeout 5", "goes with --workers");
    ExpectRefused("serve --listen 127.0.0.1:99999", "--listen");
    ExpectRefused("serve --listen \"127.0.0.1: 5\"", "contains a space");
}

TEST_F(Remote, MalformedAndHostileMessagesNeverTakeTheServerDown) {
    Server server(Path("s.log"));
    ASSERT_GT(server.Port(), 0);
    // Random bytes, a truncated message, and a segment table claiming an enormous message.
    std::string random;
    for (int i = 0; i < 4096; ++i) random += static_cast<char>((i * 2654435761u) >> 13);
    SendRaw(server.Port(), random);
    capnp::MallocMessageBuilder builder;
    builder.initRoot<app::schema::EvalRequest>().initShape().initSine().setAmplitude(4.1);
    const auto words = capnp::messageToFlatArray(builder);
    const auto bytes = words.asBytes();
    SendRaw(server.Port(), std::string(reinterpret_cast<const char*>(bytes.begin()), bytes.size() / 2));
    SendRaw(server.Port(), std::string("\x00\x00\x00\x00\xff\xff\xff\x7f", 8) + std::string(64, '\0'));

    capnp::EzRpcClient client(server.Address());
    auto evaluator = client.getMain<app::schema::Evaluator>();
    auto& waitScope = client.getWaitScope();
    auto request = [&](auto fill) {
        auto call = evaluator.evaluateRequest();
        auto list = call.initRequests(1);
        list[0].initShape().initSine().setAmplitude(4.1);
        list[0].getShape().getSine().setPhaseEnd(2.64);
        list[0].initParams().setIterations(200);
        list[0].initMeshSize();
        fill(list[0]);
        return call.send();
    };
    // Semantically bad requests get an error reply naming the problem.
    const std::vector<std::pair<std::string, std::function<void(app::schema::EvalRequest::Builder)>>> bad{
        {"NaN amplitude", [](auto r) { r.getShape().getSine().setAmplitude(NAN); }},
        {"huge mesh", [](auto r) { r.getMeshSize().setResolution(100000); }},
        {"too many iterations", [](auto r) { r.getParams().setIterations(2000000000); }},
        {"infinite constant", [](auto r) { r.getParams().setStepScale(INFINITY); }},
        {"three-point spline", [](auto r) {
             auto spline = r.getShape().initBspline().initSplines(1)[0].initControlPoints(3);
             spline.set(0, 1);
         }},
    };
    for (const auto& [what, fill] : bad) {
        try {
            request(fill).wait(waitScope);
            ADD_FAILURE() << what << " was accepted";
        } catch (const kj::Exception& error) {
            EXPECT_THAT(std::string(error.getDescription().cStr()), HasSubstr("bad evaluation request")) << what;
        }
    }
    const app::ServerLimits limits;
    auto tooMany = evaluator.evaluateRequest();
    tooMany.initRequests(limits.maxRequests + 1);
    EXPECT_THROW(tooMany.send().wait(waitScope), kj::Exception);
    // Inside the count limit, but the reply would pass the size bound: refused, not attempted.
    auto tooLarge = evaluator.evaluateRequest();
    auto large = tooLarge.initRequests(400);
    for (unsigned k = 0; k < large.size(); ++k) {
        large[k].initShape().setCylinder();
        large[k].initParams().setIterations(10);
        large[k].initMeshSize().setResolution(256);
        large[k].getMeshSize().setTurns(256);
    }
    try {
        tooLarge.send().wait(waitScope);
        ADD_FAILURE() << "400 shapes of 256 x 256 were accepted in one call";
    } catch (const kj::Exception& error) {
        EXPECT_THAT(std::string(error.getDescription().cStr()), HasSubstr("the reply would take"));
    }

    // And a good request is still answered, correctly.
    auto good = request([](auto) {}).wait(waitScope);
    ASSERT_EQ(good.getResponses().size(), 1u);
    EXPECT_EQ(good.getResponses()[0].getResult().getStatus(), app::schema::Status::OK);
    EXPECT_EQ(good.getResponses()[0].getFinal().getX().size(), 900u);
    EXPECT_TRUE(server.Alive());
    auto info = evaluator.infoRequest().send().wait(waitScope);
    EXPECT_EQ(info.getMaxVertices(), limits.maxVertices);
    EXPECT_GT(info.getMaxReplyWords(), 0u);
}

TEST_F(Remote, AHungServerTimesOutAndItsShapesGoToTheOthers) {
    // A "server" that accepts connections and never answers.
    const int listener = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
    ASSERT_EQ(bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(listen(listener, 4), 0);
    socklen_t length = sizeof address;
    getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length);
    const int hungPort = ntohs(address.sin_port);

    Server good(Path("good.log"));
    ASSERT_GT(good.Port(), 0);
    // Long enough (sixty 10,000-iteration shapes on one server thread, about 2.5 s) for the timeout to pass.
    ASSERT_EQ(Run("sweep " + Sweep(60, 10000) + " --out " + Path("local")).exitCode, 0);
    const Result r = Run("sweep " + Sweep(60, 10000) + " --out " + Path("remote") + " --worker-timeout 1 --workers 127.0.0.1:" +
                         std::to_string(hungPort) + "," + good.Address());
    close(listener);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("no answer within the worker timeout"));
    EXPECT_EQ(Slurp(dir_ / "remote" / "results.csv"), Slurp(dir_ / "local" / "results.csv"));
}

// A request is checked with the command line's field ranges, and every call, one shape or many, is
// bounded by the work limit; calls beyond what the threads can run wait their turn; a call whose
// client has gone is dropped rather than computed.
TEST_F(Remote, RequestsAreRangedBoundedQueuedAndDroppedWithTheirClient) {
    Server server(Path("s.log"));
    ASSERT_GT(server.Port(), 0);
    auto shellJob = [](auto edit) {
        sim::EvalJob job;
        job.SetModel(sim::ModelKind::Shell);
        job.Shell() = sim::DefaultShellDef();
        job.Shell().geometry.ringVertices = 12;
        job.Shell().geometry.rings = 16;
        job.shape = sim::CylinderShape{};
        edit(job);
        return job;
    };
    auto refusal = [&](const std::vector<sim::EvalJob>& jobs) -> std::string {
        capnp::EzRpcClient client(server.Address());
        auto call = client.getMain<app::schema::Evaluator>().evaluateRequest();
        auto list = call.initRequests(static_cast<unsigned>(jobs.size()));
        for (unsigned k = 0; k < jobs.size(); ++k) app::SetJob(list[k], jobs[k]);
        try {
            call.send().wait(client.getWaitScope());
        } catch (const kj::Exception& error) {
            return error.getDescription().cStr();
        }
        return "accepted";
    };
    EXPECT_THAT(refusal({shellJob([](auto& j) { j.Shell().solver.maxBisections = 31; })}), HasSubstr("max_bisections: 31 is out of range (0 to 30)"));
    EXPECT_THAT(refusal({shellJob([](auto& j) { j.Shell().geometry.lengthMm = 1e6; })}), HasSubstr("length_mm: 1e+06 is out of range"));
    // One shape alone, inside every field's range, but asking for more work than a call may.
    EXPECT_THAT(refusal({shellJob([](auto& j) {
                    j.Shell().geometry.ringVertices = 200;
                    j.Shell().geometry.rings = 200;
                    j.Shell().load.steps = 1000;
                    j.Shell().solver.maxIterations = 10000;
                })}),
                HasSubstr("units of work, more than"));

    // A long call (40 thesis shapes of 300,000 steps, about 20 s on the server's one thread) whose
    // client goes away after a moment: the server says so and answers the next call at once.
    {
        capnp::EzRpcClient doomed(server.Address());
        auto call = doomed.getMain<app::schema::Evaluator>().evaluateRequest();
        auto list = call.initRequests(40);
        for (unsigned k = 0; k < 40; ++k) {
            sim::EvalJob job;
            job.shape = sim::SineShape{1 + 0.01 * k, 0.5, 2.64};
            job.Thesis().params.iterations = 300000;
            app::SetJob(list[k], job);
        }
        auto pending = call.send();
        doomed.getWaitScope().poll();
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        doomed.getWaitScope().poll();
    }  // the client and its call are gone
    testing_support::WaitUntil([&] { return Slurp(Path("s.log")).find("a call was dropped by its client") != std::string::npos; }, 10);
    EXPECT_THAT(Slurp(Path("s.log")), HasSubstr("shapes not evaluated"));

    // Three clients at once: their calls queue and each gets its own answer.
    std::vector<std::thread> clients;
    std::vector<double> fitness(3, NAN);
    for (int c = 0; c < 3; ++c)
        clients.emplace_back([&, c] {
            capnp::EzRpcClient client(server.Address());
            auto call = client.getMain<app::schema::Evaluator>().evaluateRequest();
            sim::EvalJob job;
            job.shape = sim::SineShape{1.0 + c, 0.5, 2.64};
            job.Thesis().params.iterations = 3000;
            app::SetJob(call.initRequests(1)[0], job);
            fitness[c] = call.send().wait(client.getWaitScope()).getResponses()[0].getResult().getFitness();
        });
    for (auto& t : clients) t.join();
    for (int c = 0; c < 3; ++c) {
        sim::EvalJob job;
        job.shape = sim::SineShape{1.0 + c, 0.5, 2.64};
        job.Thesis().params.iterations = 3000;
        EXPECT_EQ(fitness[c], sim::Evaluate(job).fitness) << "client " << c;
    }
    EXPECT_TRUE(server.Alive());
}
