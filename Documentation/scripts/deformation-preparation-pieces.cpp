// The pieces of a deformation's preparation on conference, each the median of 100.
#include "linkgi/Scenes.h"
#include "linkgi/Scene.h"
#include "linkgi/Parallel.h"
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <vector>
using namespace linkgi;
template <typename T> bool sameAll(const std::vector<T>& a, const std::vector<T>& b){
  constexpr std::size_t kChunk = 256 << 10; const std::size_t bytes=a.size()*sizeof(T);
  if (a.size()!=b.size()||bytes<=kChunk) return sameBits(a,b);
  const auto* x=reinterpret_cast<const unsigned char*>(a.data()); const auto* y=reinterpret_cast<const unsigned char*>(b.data());
  std::atomic<bool> d{false};
  parallelRanges((bytes+kChunk-1)/kChunk,1,[&](std::size_t s,std::size_t e){for(std::size_t c=s;c<e&&!d;++c){std::size_t f=c*kChunk,z=std::min(bytes,f+kChunk)-f; if(std::memcmp(x+f,y+f,z))d=true;}});
  return !d;
}
double med(const std::function<void()>& f){ std::vector<double> t; for(int i=0;i<100;++i){auto s=std::chrono::steady_clock::now(); f(); t.push_back(std::chrono::duration<double,std::milli>(std::chrono::steady_clock::now()-s).count());} std::sort(t.begin(),t.end()); return t[50]; }
int main(){
  Scene scene=makeStandardScene("conference"); validateScene(scene);
  Scene deformed=scene; for(auto&p:deformed.positions)p.y*=1.03f;
  Scene cached=scene; volatile std::size_t sink=0;
  std::printf("workers %d\n", workerCount());
  std::printf("empty dispatch (8 chunks) %.4f ms\n", med([&]{ parallelRanges(8,1,[&](std::size_t,std::size_t){}); }));
  std::printf("compare 4 same arrays on all cores %.3f ms\n", med([&]{ sink+=sameAll(scene.triangles,cached.triangles)+sameAll(scene.normals,cached.normals)+sameAll(scene.albedo,cached.albedo)+sameAll(scene.emission,cached.emission); }));
  std::printf("compare 4 same arrays one core %.3f ms\n", med([&]{ sink+=sameBits(scene.triangles,cached.triangles)+sameBits(scene.normals,cached.normals)+sameBits(scene.albedo,cached.albedo)+sameBits(scene.emission,cached.emission); }));
  std::printf("copy positions, fresh vector %.3f ms\n", med([&]{ std::vector<Vec3f> v=deformed.positions; sink+=v.size(); }));
  std::vector<Vec3f> buf=deformed.positions;
  std::printf("copy positions, same buffer, one core %.3f ms\n", med([&]{ std::memcpy(buf.data(),deformed.positions.data(),buf.size()*12); }));
  std::printf("bounds %.3f ms\n", med([&]{ Vec3f lo,hi; positionBounds(deformed.positions,lo,hi); sink+=lo.x>0; }));
  std::printf("finite %.3f ms\n", med([&]{ sink+=firstIndexWhere(deformed.positions.size(),16384,[&](std::size_t i){return !isFinite(deformed.positions[i]);}); }));
  std::printf("degenerate %.3f ms\n", med([&]{ const auto& P=deformed.positions; const auto& T=deformed.triangles; sink+=firstIndexWhere(T.size(),16384,[&](std::size_t i){const Triangle&t=T[i]; if(t.v[0]==t.v[1]||t.v[1]==t.v[2]||t.v[0]==t.v[2])return true; Vec3f n=cross(P[t.v[1]]-P[t.v[0]],P[t.v[2]]-P[t.v[0]]); return !(dot(n,n)>0.f);}); }));
  KnownValid k; k.normals=k.triangles=k.albedo=k.emission=true; Scene s=deformed; std::vector<std::string> w;
  std::printf("validateChanges (positions) %.3f ms\n", med([&]{ sink+=validateChanges(s,AlbedoPolicy::Clamp,k,w); }));
  std::printf("validateScene (all, on a copy) %.3f ms\n", med([&]{ Scene c=deformed; validateScene(c); sink+=c.triangles.size(); }));
}
