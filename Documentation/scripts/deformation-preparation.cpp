// The orchestrator's preparation of a deformation (conference, 3% stretch): the time from
// update() to the first stage's progress call, which aborts the update (the cache stays the
// undeformed scene, so every call prepares the same deformation). Median of N.
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"
#include "linkgi/Error.h"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
using namespace linkgi;
int main(int argc, char** argv){
  const int n = argc > 1 ? std::atoi(argv[1]) : 40;
  const bool cuda = argc > 2 && std::string(argv[2]) == "cuda";
  Scene scene=makeStandardScene("conference");
  Scene deformed=scene; for(auto&p:deformed.positions)p.y*=1.03f;
  SolverOptions o; o.method=Method::InstantRadiosity; o.backend=cuda ? Backend::Cuda : Backend::Cpu;
  o.instantRadiosity.vplCount=cuda ? 4096 : 64; o.instantRadiosity.interleave=64; o.instantRadiosity.proxyVisibility=true; o.instantRadiosity.proxyResolution=16;
  Solver solver; solver.update(scene,o);
  std::vector<double> t;
  for(int i=0;i<n;++i){
    std::chrono::steady_clock::time_point start=std::chrono::steady_clock::now(), hit;
    try { solver.update(deformed,o,[&](const char*,double){ hit=std::chrono::steady_clock::now(); return false; }); }
    catch (const Aborted&) {}
    t.push_back(std::chrono::duration<double,std::milli>(hit-start).count());
  }
  std::sort(t.begin(),t.end());
  std::printf("prepare-to-first-stage ms (%s): median %.3f  p10 %.3f  p90 %.3f\n", solver.stats().device.c_str(), t[t.size()/2], t[t.size()/10], t[t.size()*9/10]);
}
