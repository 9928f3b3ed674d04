// Timing driver for ROS navfn (ros-planning/navigation, navfn/src/navfn.cpp, unchanged), built by build.sh in a
// temporary folder from a navigation checkout: navfn's code is never part of this repository. Commands on standard
// input, one answer line each on standard output (NavfnComparison in tests/sabot.planner.benchmarks drives it):
//
//   load FILE.pgm                          raw 8-bit costmap (ROS costmap_2d values), image row 0 first; a one-cell
//                                          lethal ring is added around it (navfn forces its own outer ring to
//                                          lethal; with the ring both planners see the same passable cells)
//                                          -> "ok WIDTH HEIGHT"
//   time whole|makeplan SX SY GX GY N      N calls, cells of the unpadded image (column, row from the top):
//                                          whole:    setStart(S) setGoal(G) calcNavFnDijkstra(false), the full
//                                                    propagation from the goal, then navfn's path from the start
//                                          makeplan: as NavfnROS::makePlan calls it, setStart(G) setGoal(S)
//                                                    calcNavFnDijkstra(true): propagation from the robot, stopped
//                                                    once the goal cell has a value, then the path
//                                          field:    the navigation function alone: what calcNavFnDijkstra(false)
//                                                    does before its path (setupNavFn(true), propNavFnDijkstra with
//                                                    its cycle limit); the result has no path
//                                          -> "times MS MS ..." (wall clock), "cpu MS MS ..." (CPU time of the
//                                          calling thread, the same calls) then "result REACHED PATHLEN X Y X Y
//                                          ..." (path in unpadded image cells, from where the path starts)
//   quit
#include <navfn/navfn.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

bool readPgm(const std::string &file, int &width, int &height, std::vector<unsigned char> &pixels) {
    std::ifstream in(file, std::ios::binary);
    std::string magic;
    int maxValue = 0;
    if (!(in >> magic) || magic != "P5") {
        return false;
    }
    auto next = [&in](int &value) {
        while (true) {
            in >> std::ws;
            if (in.peek() == '#') {
                std::string comment;
                std::getline(in, comment);
                continue;
            }
            return static_cast<bool>(in >> value);
        }
    };
    if (!next(width) || !next(height) || !next(maxValue) || maxValue > 255) {
        return false;
    }
    in.get();
    pixels.resize(static_cast<size_t>(width) * height);
    in.read(reinterpret_cast<char *>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
    return static_cast<bool>(in);
}

/** CPU time of the calling thread, ms: on a shared machine, the time the call itself took of a core. */
double threadCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

}  // namespace

int main() {
    std::ios::sync_with_stdio(false);
    navfn::NavFn *planner = nullptr;
    int width = 0;
    int height = 0;
    std::string line;
    while (std::getline(std::cin, line)) {
        std::istringstream command(line);
        std::string verb;
        command >> verb;
        if (verb == "quit") {
            break;
        }
        if (verb == "load") {
            std::string file;
            command >> file;
            std::vector<unsigned char> pixels;
            if (!readPgm(file, width, height, pixels)) {
                std::cout << "error cannot read 8-bit P5 image " << file << std::endl;
                continue;
            }
            int nx = width + 2;
            int ny = height + 2;
            std::vector<unsigned char> padded(static_cast<size_t>(nx) * ny, COST_OBS);
            for (int row = 0; row < height; row++) {
                for (int column = 0; column < width; column++) {
                    padded[static_cast<size_t>(row + 1) * nx + column + 1] = pixels[static_cast<size_t>(row) * width + column];
                }
            }
            delete planner;
            planner = new navfn::NavFn(nx, ny);
            planner->setCostmap(padded.data(), true, true);  // as NavfnROS::makePlan, allow_unknown default true
            std::cout << "ok " << width << " " << height << std::endl;
            continue;
        }
        if (verb == "time" && planner != nullptr) {
            std::string mode;
            int start[2];
            int goal[2];
            int repeat = 0;
            command >> mode >> start[0] >> start[1] >> goal[0] >> goal[1] >> repeat;
            bool makePlan = mode == "makeplan";
            bool field = mode == "field";
            start[0]++, start[1]++, goal[0]++, goal[1]++;  // the lethal ring
            std::ostringstream times;
            std::ostringstream cpu;
            times << "times";
            cpu << "cpu";
            for (int i = 0; i < repeat; i++) {
                double cpuBegin = threadCpuMs();
                auto begin = std::chrono::steady_clock::now();
                if (makePlan) {
                    planner->setStart(goal);
                    planner->setGoal(start);
                    planner->calcNavFnDijkstra(true);
                } else if (field) {
                    planner->setStart(start);
                    planner->setGoal(goal);
                    planner->setupNavFn(true);
                    int cycles = std::max(planner->nx * planner->ny / 20, planner->nx + planner->ny);
                    planner->propNavFnDijkstra(cycles, false);  // the cycle limit calcNavFnDijkstra passes
                } else {
                    planner->setStart(start);
                    planner->setGoal(goal);
                    planner->calcNavFnDijkstra(false);
                }
                auto end = std::chrono::steady_clock::now();
                cpu << " " << threadCpuMs() - cpuBegin;
                times << " " << std::chrono::duration<double, std::milli>(end - begin).count();
            }
            std::cout << times.str() << std::endl;
            std::cout << cpu.str() << std::endl;
            long reached = 0;
            for (int i = 0; i < planner->ns; i++) {
                if (planner->potarr[i] < POT_HIGH) {
                    reached++;
                }
            }
            std::ostringstream result;
            int length = field ? 0 : planner->getPathLen();
            result << "result " << reached << " " << length;
            float *x = planner->getPathX();
            float *y = planner->getPathY();
            for (int i = 0; i < length; i++) {
                result << " " << (x[i] - 1) << " " << (y[i] - 1);
            }
            std::cout << result.str() << std::endl;
            continue;
        }
        std::cout << "error unknown command or no map loaded: " << line << std::endl;
    }
    delete planner;
    return 0;
}
