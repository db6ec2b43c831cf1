#include "fuzz_mesh_input.h"

#include <stdlib.h>
#include <string.h>

/* Little-endian reads that treat bytes past the end as zero. */
static uint64_t read_le(const uint8_t* data, size_t size, size_t offset, size_t bytes) {
    uint64_t value = 0;
    for (size_t i = 0; i < bytes; ++i) {
        if (offset + i < size) value |= (uint64_t)data[offset + i] << (8 * i);
    }
    return value;
}

static void write_le(uint8_t* out, uint64_t value, size_t bytes) {
    for (size_t i = 0; i < bytes; ++i) out[i] = (uint8_t)(value >> (8 * i));
}

void fuzz_mesh_input_decode(const uint8_t* data, size_t size, fuzz_mesh_input* input) {
    memset(input, 0, sizeof(*input));
    input->domain = (uint8_t)(read_le(data, size, 0, 1) % 3);
    input->flags = (uint8_t)read_le(data, size, 1, 1);
    input->point_padding = (uint8_t)(read_le(data, size, 2, 1) % 16);
    input->setting_count = (size_t)(read_le(data, size, 3, 1) % FUZZ_MAX_SETTINGS);
    const size_t points_asked = (size_t)read_le(data, size, 4, 2);
    input->cancel_at = (uint8_t)read_le(data, size, 6, 1);
    input->polygons = (uint8_t)read_le(data, size, 7, 1);
    size_t offset = FUZZ_HEADER_BYTES;
    for (size_t s = 0; s < input->setting_count; ++s) {
        input->settings[s].selector = (uint8_t)read_le(data, size, offset, 1);
        input->settings[s].raw = read_le(data, size, offset + 1, 8);
        offset += FUZZ_SETTING_BYTES;
    }
    const size_t coordinate = (input->flags & FUZZ_FLAG_F64) ? 8 : 4;
    input->point_stride = 3 * coordinate + input->point_padding;
    const size_t available = offset < size ? size - offset : 0;
    input->point_count = points_asked;
    if (input->point_count > available / input->point_stride) {
        input->point_count = available / input->point_stride;
    }
    input->points = offset < size ? data + offset : data;
    offset += input->point_count * input->point_stride;
    const size_t index_bytes = (input->flags & FUZZ_FLAG_U16) ? 2 : 4;
    input->indices = offset < size ? data + offset : data;
    input->index_count = offset < size ? (size - offset) / index_bytes : 0;
}

fuzz_setting fuzz_int_setting(int32_t param, int64_t value) {
    fuzz_setting s;
    s.selector = (uint8_t)(param & 0x3f);
    s.raw = (uint64_t)value;
    return s;
}

fuzz_setting fuzz_float_setting(int32_t param, double value) {
    fuzz_setting s;
    s.selector = (uint8_t)(param & 0x3f);
    memcpy(&s.raw, &value, sizeof(value));
    return s;
}

uint8_t* fuzz_mesh_seed_encode(const fuzz_mesh_seed* seed, size_t* size) {
    if (seed->vertex_count > 0xffff || seed->setting_count > FUZZ_MAX_SETTINGS - 1) return NULL;
    const int f64 = (seed->flags & FUZZ_FLAG_F64) != 0, u16 = (seed->flags & FUZZ_FLAG_U16) != 0;
    const size_t coordinate = f64 ? 8 : 4, index_bytes = u16 ? 2 : 4;
    const size_t padding = seed->point_padding % 16;
    const size_t stride = 3 * coordinate + padding;
    *size = FUZZ_HEADER_BYTES + FUZZ_SETTING_BYTES * seed->setting_count +
            stride * seed->vertex_count + index_bytes * seed->index_count;
    uint8_t* out = calloc(*size, 1);
    if (!out) return NULL;
    out[0] = seed->domain;
    out[1] = seed->flags;
    out[2] = (uint8_t)padding;
    out[3] = (uint8_t)seed->setting_count;
    write_le(out + 4, seed->vertex_count, 2);
    out[6] = seed->cancel_at;
    out[7] = seed->polygons;
    uint8_t* at = out + FUZZ_HEADER_BYTES;
    for (size_t s = 0; s < seed->setting_count; ++s, at += FUZZ_SETTING_BYTES) {
        at[0] = seed->settings[s].selector;
        write_le(at + 1, seed->settings[s].raw, 8);
    }
    for (size_t v = 0; v < seed->vertex_count; ++v, at += stride) {
        for (int c = 0; c < 3; ++c) {
            const double x = seed->positions[3 * v + (size_t)c];
            if (f64) {
                memcpy(at + 8 * c, &x, 8);
            } else {
                const float xf = (float)x;
                memcpy(at + 4 * c, &xf, 4);
            }
        }
    }
    for (size_t i = 0; i < seed->index_count; ++i, at += index_bytes) {
        if (u16 && seed->indices[i] > 0xffff) {
            free(out);
            return NULL;
        }
        write_le(at, seed->indices[i], index_bytes);
    }
    return out;
}
