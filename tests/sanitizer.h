// Whether a test is compiled with AddressSanitizer (scripts/dev.sh sanitize):
// LOOPTESS_ASAN is defined then, so tests too heavy for that run can skip or shrink
// (each says why).
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define LOOPTESS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LOOPTESS_ASAN 1
#endif
#endif
