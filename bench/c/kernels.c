/* The C versions of bench/st/kernels.st, compiled with the project's C
   compiler at -O2.  Same algorithms, same types, same string semantics
   (bounded copies, byte comparison). */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

int32_t c_sieve(int32_t n, bool* flags) {
  for (int32_t i = 0; i <= n; ++i) flags[i] = true;
  for (int32_t i = 2; i * i <= n; ++i)
    if (flags[i])
      for (int32_t j = i * i; j <= n; j += i) flags[j] = false;
  int32_t count = 0;
  for (int32_t i = 2; i <= n; ++i)
    if (flags[i]) ++count;
  return count;
}

int32_t c_bubble(int32_t* a) {
  for (int32_t i = 0; i <= 1998; ++i)
    for (int32_t j = 0; j <= 1998 - i; ++j)
      if (a[j] > a[j + 1]) {
        int32_t t = a[j];
        a[j] = a[j + 1];
        a[j + 1] = t;
      }
  return a[0];
}

double c_realmath(int32_t n) {
  double acc = 0;
  for (int32_t i = 1; i <= n; ++i) {
    double x = (double)i * 0.001;
    acc = acc + sin(x) * cos(x) + sqrt(x);
  }
  return acc;
}

static void assign(char* dst, size_t cap, const char* src) {
  size_t n = strlen(src);
  if (n > cap) n = cap;
  memmove(dst, src, n);
  dst[n] = 0;
}

static void append(char* dst, size_t cap, const char* src) {
  size_t have = strlen(dst), n = strlen(src);
  if (have + n > cap) n = cap > have ? cap - have : 0;
  memmove(dst + have, src, n);
  dst[have + n] = 0;
}

int32_t c_strings(int32_t n) {
  int32_t total = 0;
  char s[81];
  for (int32_t i = 1; i <= n; ++i) {
    char tmp[81];
    assign(s, 80, "abc");
    tmp[0] = 0;
    append(tmp, 80, s);
    append(tmp, 80, "defghij");
    assign(s, 80, tmp);
    if (strcmp(s, "abcdefghij") == 0) total += (int32_t)strlen(s);
  }
  return total;
}
