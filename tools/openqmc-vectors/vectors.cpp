// Test-vector generator for the Rust port in openqmc.rs.
//
// Uses only OpenQMC's public API (oqmc::SobolBnSampler, oqmc::SobolSampler)
// from the headers at commit 294d65627f667b668373250a751862232cf21d65.
//
// Build (the CMake default OPENQMC_ARCH_TYPE=Scalar defines OQMC_FORCE_SCALAR):
//   g++ -std=c++17 -O2 -DOQMC_FORCE_SCALAR -I upstream/include vectors.cpp -o vectors
//   ./vectors > vectors.txt
// The SSE2 (plain g++ on x86-64) and AVX2 (-mavx2) builds must print the same.
//
// Output format, one line per (sampler, pixel, frame, index, domain chain):
//   <S> <x> <y> <frame> <index> <chain>
//     u1 <h> u2 <h> <h> u4 <h> <h> <h> <h>
//     f1 <b> f2 <b> <b> f4 <b> <b> <b> <b> r4 <h> <h> <h> <h>
// S is "bn" (SobolBnSampler) or "so" (SobolSampler). <chain> is "root", or a
// dot separated list of newDomain keys applied in order ("3.7" means
// root.newDomain(3).newDomain(7)); the special chains "sp:<key>:<size>:<i>",
// "di:<key>:<i>" and "ch:<key>:<i>" mean newDomainSplit / newDomainDistrib /
// newDomainChain applied to root. u* are drawSample<N>(uint32_t*) outputs, f*
// are drawSample<N>(float*) outputs printed as the IEEE-754 bit pattern, r4 is
// drawRnd<4>(uint32_t*). All values in 8-digit lowercase hex.
// Lines beginning with '#' are comments.

#include <oqmc/sobol.h>
#include <oqmc/sobolbn.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace
{

struct Chain
{
	std::string name;
	int kind;              // 0: plain newDomain list, 1: split, 2: distrib, 3: chain
	std::vector<int> keys; // kind 0: keys; kind 1: key,size,index; 2/3: key,index
};

std::uint32_t floatBits(float f)
{
	std::uint32_t u;
	std::memcpy(&u, &f, sizeof(u));
	return u;
}

template <typename Sampler>
Sampler applyChain(Sampler s, const Chain& c)
{
	switch(c.kind)
	{
	case 0:
		for(int k : c.keys)
		{
			s = s.newDomain(k);
		}
		return s;
	case 1:
		return s.newDomainSplit(c.keys[0], c.keys[1], c.keys[2]);
	case 2:
		return s.newDomainDistrib(c.keys[0], c.keys[1]);
	default:
		return s.newDomainChain(c.keys[0], c.keys[1]);
	}
}

long long lines = 0;

template <typename Sampler>
void emit(const char* tag, const void* cache, int x, int y, int frame,
          int index, const Chain& c)
{
	const auto root = Sampler(x, y, frame, index, cache);
	const auto d = applyChain(root, c);

	std::uint32_t u1[1], u2[2], u4[4], r4[4];
	float f1[1], f2[2], f4[4];

	d.template drawSample<1>(u1);
	d.template drawSample<2>(u2);
	d.template drawSample<4>(u4);
	d.template drawSample<1>(f1);
	d.template drawSample<2>(f2);
	d.template drawSample<4>(f4);
	d.template drawRnd<4>(r4);

	std::printf("%s %d %d %d %d %s u1 %08x u2 %08x %08x u4 %08x %08x %08x %08x"
	            " f1 %08x f2 %08x %08x f4 %08x %08x %08x %08x"
	            " r4 %08x %08x %08x %08x\n",
	            tag, x, y, frame, index, c.name.c_str(), u1[0], u2[0], u2[1],
	            u4[0], u4[1], u4[2], u4[3], floatBits(f1[0]), floatBits(f2[0]),
	            floatBits(f2[1]), floatBits(f4[0]), floatBits(f4[1]),
	            floatBits(f4[2]), floatBits(f4[3]), r4[0], r4[1], r4[2], r4[3]);
	++lines;
}

void emitBoth(const void* bnCache, const void* soCache, int x, int y,
              int frame, int index, const Chain& c)
{
	emit<oqmc::SobolBnSampler>("bn", bnCache, x, y, frame, index, c);
	emit<oqmc::SobolSampler>("so", soCache, x, y, frame, index, c);
}

} // namespace

int main()
{
	// Cache initialisation as in OpenQMC's README (step 2).
	auto bnCache = new char[oqmc::SobolBnSampler::cacheSize];
	oqmc::SobolBnSampler::initialiseCache(bnCache);

	// SobolSampler::cacheSize is 0; allocate at least one byte.
	auto soCache = new char[oqmc::SobolSampler::cacheSize + 1];
	oqmc::SobolSampler::initialiseCache(soCache);

	const int pixels[][2] = {
	    {0, 0},     {1, 0},     {0, 1},      {17, 42},   {255, 255},
	    {256, 0},   {300, 700}, {511, 257},  {1023, 4095}, {-1, -3},
	};

	const int frames[] = {0, 1, 1000, 123456};

	std::vector<int> indices;
	for(int i = 0; i <= 70; ++i)
	{
		indices.push_back(i);
	}
	for(int i : {255, 256, 1023, 65535, 65536, (1 << 20) + 3})
	{
		indices.push_back(i);
	}

	const Chain root = {"root", 0, {}};
	const Chain nested = {"3.7", 0, {3, 7}};

	std::vector<Chain> keyChains;
	for(int k = 0; k < 40; ++k)
	{
		keyChains.push_back({std::to_string(k), 0, {k}});
	}

	std::printf("# OpenQMC 294d65627f667b668373250a751862232cf21d65 test vectors\n");

	// Block A: every pixel x frame x index, for root and the nested chain.
	std::printf("# block A\n");
	for(const auto& p : pixels)
		for(int f : frames)
			for(int i : indices)
				for(const Chain* c : {&root, &nested})
					emitBoth(bnCache, soCache, p[0], p[1], f, i, *c);

	// Block B: every newDomain(k), k in [0, 40), on a subset of pixels and
	// indices, all frames.
	std::printf("# block B\n");
	const int pixelsB[][2] = {{0, 0}, {17, 42}, {511, 257}};
	const int indicesB[] = {0, 1, 2, 31, 255, 65536};
	for(const auto& p : pixelsB)
		for(int f : frames)
			for(int i : indicesB)
				for(const auto& c : keyChains)
					emitBoth(bnCache, soCache, p[0], p[1], f, i, c);

	// Block C: every newDomain(k) for indices 0..31 at one pixel/frame.
	std::printf("# block C\n");
	for(int i = 0; i < 32; ++i)
		for(const auto& c : keyChains)
			emitBoth(bnCache, soCache, 5, 9, 1, i, c);

	// Block D: deeper chains and the split / distrib / chain variants that
	// OpenQMC's trace tool uses for light samples.
	std::printf("# block D\n");
	const std::vector<Chain> extra = {
	    {"1.0.4.2", 0, {1, 0, 4, 2}},
	    {"0.0.0.0.0", 0, {0, 0, 0, 0, 0}},
	    {"1000000.-5", 0, {1000000, -5}},
	    {"sp:1:4:0", 1, {1, 4, 0}},
	    {"sp:1:4:3", 1, {1, 4, 3}},
	    {"sp:2:7:6", 1, {2, 7, 6}},
	    {"di:1:0", 2, {1, 0}},
	    {"di:1:5", 2, {1, 5}},
	    {"di:3:70000", 2, {3, 70000}},
	    {"ch:1:0", 3, {1, 0}},
	    {"ch:1:5", 3, {1, 5}},
	};
	for(const auto& p : pixelsB)
		for(int f : frames)
			for(int i : {0, 1, 5, 64, 255, 65535, 65536})
				for(const auto& c : extra)
					emitBoth(bnCache, soCache, p[0], p[1], f, i, c);

	// Block E: a pixel scan (one row, one column, diagonal) at the root.
	std::printf("# block E\n");
	for(int t = 0; t < 300; ++t)
	{
		emitBoth(bnCache, soCache, t, 0, 0, 0, root);
		emitBoth(bnCache, soCache, 0, t, 0, 0, root);
		emitBoth(bnCache, soCache, t, t, 7, 3, keyChains[1]);
	}

	std::printf("# end %lld\n", lines);

	delete[] bnCache;
	delete[] soCache;

	return 0;
}
