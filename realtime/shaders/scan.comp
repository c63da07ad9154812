// Exclusive prefix sum of uCount uints in place, the total written after them (data[uCount]):
// BLOCKS scans each block of 1024 values and keeps its total, SUMS scans the block totals in one
// work group, ADD adds each block's offset. Integer sums: the result does not depend on
// scheduling.
layout(local_size_x = 256) in;

uniform uint uCount;
uniform uint uOffset;  // the first value, in uints from the buffer's start

layout(std430, binding = 5) buffer Data {
    uint data[];
};
layout(std430, binding = 6) buffer BlockSums {
    uint blockSums[];  // one per block, then their total
};

const uint PER_THREAD = 4u, BLOCK = 256u * PER_THREAD;
shared uint partial[256];

// Exclusive scan of partial[] (one value per invocation), by Hillis and Steele; returns the
// total.
uint scanShared(uint own) {
    uint t = gl_LocalInvocationID.x;
    partial[t] = own;
    barrier();
    for (uint stride = 1u; stride < 256u; stride *= 2u) {
        uint add = t >= stride ? partial[t - stride] : 0u;
        barrier();
        partial[t] += add;
        barrier();
    }
    uint total = partial[255];
    uint exclusive = partial[t] - own;
    barrier();
    partial[t] = exclusive;
    barrier();
    return total;
}

#ifdef BLOCKS
void main() {
    uint base = gl_WorkGroupID.x * BLOCK + gl_LocalInvocationID.x * PER_THREAD;
    uint values[PER_THREAD];
    uint sum = 0u;
    for (uint k = 0u; k < PER_THREAD; ++k) {
        values[k] = base + k < uCount ? data[uOffset + base + k] : 0u;
        sum += values[k];
    }
    uint total = scanShared(sum);
    uint running = partial[gl_LocalInvocationID.x];
    for (uint k = 0u; k < PER_THREAD; ++k) {
        if (base + k < uCount) data[uOffset + base + k] = running;
        running += values[k];
    }
    if (gl_LocalInvocationID.x == 0u) blockSums[gl_WorkGroupID.x] = total;
}
#endif

#ifdef SUMS
uniform uint uBlocks;
void main() {
    uint t = gl_LocalInvocationID.x;
    uint per = (uBlocks + 255u) / 256u;
    uint begin = min(t * per, uBlocks), end = min(begin + per, uBlocks);
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
        blockSums[uBlocks] = total;
        data[uOffset + uCount] = total;
    }
}
#endif

#ifdef ADD
void main() {
    uint base = gl_WorkGroupID.x * BLOCK;
    uint offset = blockSums[gl_WorkGroupID.x];
    for (uint k = gl_LocalInvocationID.x; k < BLOCK; k += 256u)
        if (base + k < uCount) data[uOffset + base + k] += offset;
}
#endif
