// pattern_sort.comp -- screen-space level of detail on the pattern path (DrawPath::
// Patterns, after Boubekeur and Schlick 2008): each drawn record gets the refinement
// pattern of its screen-space edge factors, rounded up to powers of two
// (record_factors.glsl, patterns.h), and the records are sorted by pattern into
// the lists that one indexed indirect draw per pattern draws (gpu_layout.h's sort
// region at word(LT_H_SORT)). Three passes, with a compute barrier between them:
//
//   COUNT    a work group per chunk of LT_SORT_CHUNK records of one list
//            (pc.base: the list's offset; pc.evaluate.x its record count, .y the
//            chunk's index over the frame's lists): its records per key -> COUNTS
//   SCAN     one work group (pc.evaluate.w: the frame's chunks): per key, the sum
//            over chunks -> the command's instance count; keys in order ->
//            first instances; each COUNTS entry becomes the chunk's first slot
//   SCATTER  as COUNT: each record to RECORDS[its chunk's first slot for its key +
//            the records of that key before it in the chunk]
//
// So the order is stable: by key, then by list and record, every frame the same
// (VulkanSurface::capture puts the captured triangles back in record order by it).
// SCATTER evaluates a record's factors again rather than storing its key.
//
// A chunk is walked in rounds of LT_SORT_LOCAL_SIZE records, one per invocation:
//
//   round r:  sKey[t] = key of record r * 128 + t   (LT_NONE past the list's end)
//             rank = #{ t' < t : sKey[t'] == key }   slot = sNext[key] + rank
//             sNext[key] += #{ t : sKey[t] == key }  (one atomic per invocation)
#version 450
#extension GL_GOOGLE_include_directive : require
#define LT_WRITE_TABLES
#include "common.glsl"
#include "record_factors.glsl"
#include "pattern_key.glsl"

layout(local_size_x = LT_SORT_LOCAL_SIZE) in;

shared uint sNext[LT_PATTERN_KEYS];   // COUNT: records per key; SCATTER: next slot per key
shared uint sKey[LT_SORT_LOCAL_SIZE];
shared uint sTotal[LT_PATTERN_KEYS];  // SCAN

uint countsAt(uint key, uint chunk) { return word(LT_H_SORT_COUNTS) + key * word(LT_H_SORT_CHUNKS) + chunk; }

void chunkPass(bool scatter) {
    uint lid = gl_LocalInvocationID.x;
    uint chunk = pc.evaluate.y + gl_WorkGroupID.x;
    for (uint k = lid; k < LT_PATTERN_KEYS; k += LT_SORT_LOCAL_SIZE)
        sNext[k] = scatter ? tables.words[countsAt(k, chunk)] : 0u;
    barrier();
    uint records = word(LT_H_SORT_RECORDS);
    for (uint round = 0u; round < LT_SORT_CHUNK / LT_SORT_LOCAL_SIZE; ++round) {
        uint r = gl_WorkGroupID.x * LT_SORT_CHUNK + round * LT_SORT_LOCAL_SIZE + lid;
        uint record = r < pc.evaluate.x ? word(pc.base + r) : LT_NONE;
        uint key = record != LT_NONE ? recordKey(record) : LT_NONE;
        if (scatter) {
            sKey[lid] = key;
            barrier();
            uint rank = 0u;
            for (uint t = 0u; t < lid; ++t) rank += sKey[t] == key ? 1u : 0u;
            if (key != LT_NONE) tables.words[records + sNext[key] + rank] = record;
            barrier();
        }
        if (key != LT_NONE) atomicAdd(sNext[key], 1u);
        barrier();
    }
    if (!scatter)
        for (uint k = lid; k < LT_PATTERN_KEYS; k += LT_SORT_LOCAL_SIZE) tables.words[countsAt(k, chunk)] = sNext[k];
}

void scan() {
    uint lid = gl_LocalInvocationID.x, chunks = pc.evaluate.w;
    for (uint k = lid; k < LT_PATTERN_KEYS; k += LT_SORT_LOCAL_SIZE) {
        uint total = 0u;
        for (uint c = 0u; c < chunks; ++c) total += tables.words[countsAt(k, c)];
        sTotal[k] = total;
    }
    barrier();
    if (lid == 0u) {
        uint first = 0u;
        for (uint k = 0u; k < LT_PATTERN_KEYS; ++k) {
            uint n = sTotal[k];
            sNext[k] = first;
            first += n;
        }
    }
    barrier();
    uint commands = word(LT_H_SORT);
    for (uint k = lid; k < LT_PATTERN_KEYS; k += LT_SORT_LOCAL_SIZE) {
        uint slot = sNext[k];
        tables.words[commands + LT_SORT_COMMAND_WORDS * k + 1u] = sTotal[k];
        tables.words[commands + LT_SORT_COMMAND_WORDS * k + 4u] = slot;
        for (uint c = 0u; c < chunks; ++c) {
            uint n = tables.words[countsAt(k, c)];
            tables.words[countsAt(k, c)] = slot;
            slot += n;
        }
    }
}

void main() {
    if (pc.level == LT_SORT_SCAN) scan();
    else chunkPass(pc.level == LT_SORT_SCATTER);
}
