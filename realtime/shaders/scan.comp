// Exclusive prefix sum of uCount uints in place, the total written after them (data[uCount]):
// BLOCKS scans each block of 16384 values and keeps its total, SUMS scans the block totals in one
// work group, ADD adds each block's offset. Integer sums: the result does not depend on
// scheduling. With uCells, the count is the grid's cells (per_set.glsl's Header, written by
// LAYOUT), and BLOCKS and ADD are dispatched indirectly over its blocks (scanDispatch).
layout(local_size_x = 256) in;

uniform uint uCount;
uniform uint uOffset;  // the first value, in uints from the buffer's start
uniform int uCells;    // count the grid's cells instead of uCount

layout(std430, binding = 5) buffer Data {
    uint data[];
};
layout(std430, binding = 19) buffer BlockSums {
    uint blockSums[];  // one per block, then their total
};
layout(std430, binding = 6) readonly buffer Header {
    uint hMinBits, nearHit, totalCells;  // per_set.glsl's Header, its first members
};

uint count() { return uCells != 0 ? totalCells : uCount; }

// 64 values per invocation: fewer work groups, each with its barriers, than 16 (the two scans of
// a 1M-particle frame's draw lists 8.8 -> 7.4 ms on llvmpipe).
const uint PER_THREAD = 64u, BLOCK = 256u * PER_THREAD;
shared uint partial[256];

// Every invocation of the work group past this point sees the shared writes before it:
// barrier() orders execution, memoryBarrierShared() makes the writes visible (GLSL 4.50 asks
// for both; a driver that runs a work group in order, as llvmpipe does, needs neither).
void sharedBarrier() {
    memoryBarrierShared();
    barrier();
}

// Exclusive scan of partial[] (one value per invocation), by Hillis and Steele; returns the
// total.
uint scanShared(uint own) {
    uint t = gl_LocalInvocationID.x;
    partial[t] = own;
    sharedBarrier();
    for (uint stride = 1u; stride < 256u; stride *= 2u) {
        uint add = t >= stride ? partial[t - stride] : 0u;
        sharedBarrier();
        partial[t] += add;
        sharedBarrier();
    }
    uint total = partial[255];
    uint exclusive = partial[t] - own;
    sharedBarrier();
    partial[t] = exclusive;
    sharedBarrier();
    return total;
}

#ifdef BLOCKS
void main() {
    uint n = count();
    uint base = gl_WorkGroupID.x * BLOCK + gl_LocalInvocationID.x * PER_THREAD;
    uint values[PER_THREAD];
    uint sum = 0u;
    for (uint k = 0u; k < PER_THREAD; ++k) {
        values[k] = base + k < n ? data[uOffset + base + k] : 0u;
        sum += values[k];
    }
    uint total = scanShared(sum);
    uint running = partial[gl_LocalInvocationID.x];
    for (uint k = 0u; k < PER_THREAD; ++k) {
        if (base + k < n) data[uOffset + base + k] = running;
        running += values[k];
    }
    if (gl_LocalInvocationID.x == 0u) blockSums[gl_WorkGroupID.x] = total;
}
#endif

#ifdef SUMS
void main() {
    uint n = count();
    uint blocks = (n + BLOCK - 1u) / BLOCK;
    uint t = gl_LocalInvocationID.x;
    uint per = (blocks + 255u) / 256u;
    uint begin = min(t * per, blocks), end = min(begin + per, blocks);
    uint sum = 0u;
    for (uint k = begin; k < end; ++k) sum += blockSums[k];
    uint total = scanShared(sum);
    uint running = partial[t];
    for (uint k = begin; k < end; ++k) {
        uint v = blockSums[k];
        blockSums[k] = running;
        running += v;
    }
    if (t == 0u) {
        blockSums[blocks] = total;
        data[uOffset + n] = total;
    }
}
#endif

#ifdef ADD
void main() {
    uint n = count();
    uint base = gl_WorkGroupID.x * BLOCK;
    uint offset = blockSums[gl_WorkGroupID.x];
    for (uint k = gl_LocalInvocationID.x; k < BLOCK; k += 256u)
        if (base + k < n) data[uOffset + base + k] += offset;
}
#endif
