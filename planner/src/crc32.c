/*
 * crc32.c - CRC-32 of model files (model.h): IEEE 802.3 / zlib polynomial 0xEDB88320
 * (reflected), initial value and final xor 0xFFFFFFFF, so Python's zlib.crc32 gives the
 * same number. A 16-entry table (two lookups per byte) keeps the code and the table small;
 * model files are at most a few tens of kilobytes, so speed does not matter here.
 */
#include "gmmrrt/model.h"

static const uint32_t crc_nibble_table[16] = {
    0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
    0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
    0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu,
};

uint32_t gmmrrt_crc32(const uint8_t *data, size_t len)
{
    uint32_t crc = 0xFFFFFFFFu;
    if (data == NULL)
        return 0u; /* crc32 of nothing */
    for (size_t i = 0; i < len; ++i) {
        crc ^= data[i];
        crc = (crc >> 4) ^ crc_nibble_table[crc & 0x0Fu];
        crc = (crc >> 4) ^ crc_nibble_table[crc & 0x0Fu];
    }
    return crc ^ 0xFFFFFFFFu;
}
