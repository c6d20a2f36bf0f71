#include "fw_link.h"

#include "fw_config.h"

static const uint32_t fw_bauds[] = FW_BAUDS;

int fw_link_baud_ok(uint32_t baud) {
  for (unsigned i = 0; i < sizeof fw_bauds / sizeof fw_bauds[0]; i++)
    if (fw_bauds[i] == baud) return 1;
  return 0;
}

uint32_t fw_link_load_permille(uint32_t frame_rate_hz, uint32_t baud) {
  if (baud == 0) return UINT32_MAX;
  uint64_t bits = (uint64_t)FW_SAMPLE_WIRE_BYTES * FW_BITS_PER_BYTE * frame_rate_hz;
  return (uint32_t)(bits * 1000u / baud);
}

int fw_link_rate_ok(uint32_t frame_rate_hz, uint32_t baud) {
  if (frame_rate_hz == 0 || frame_rate_hz > FW_TICK_HZ || FW_TICK_HZ % frame_rate_hz != 0) return 0;
  uint64_t bits = (uint64_t)FW_SAMPLE_WIRE_BYTES * FW_BITS_PER_BYTE * frame_rate_hz;
  return bits * 100u <= (uint64_t)baud * FW_LINK_MAX_PERCENT;
}
