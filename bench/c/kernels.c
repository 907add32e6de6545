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

/* 1-based, clamping string functions with the semantics of the ST ones. */
static void mid(char* dst, size_t cap, const char* s, long n, long pos) {
  size_t len = strlen(s);
  if (pos < 1 || (size_t)pos > len || n <= 0) { dst[0] = 0; return; }
  size_t k = len - (size_t)(pos - 1);
  if ((size_t)n < k) k = (size_t)n;
  if (k > cap) k = cap;
  memmove(dst, s + pos - 1, k);
  dst[k] = 0;
}
static void insert(char* dst, size_t cap, const char* a, const char* b, long pos) {
  char tmp[256];
  size_t la = strlen(a), lb = strlen(b), p = pos < 0 ? 0 : (size_t)pos > la ? la : (size_t)pos;
  memcpy(tmp, a, p);
  memcpy(tmp + p, b, lb);
  memcpy(tmp + p + lb, a + p, la - p);
  size_t k = la + lb;
  if (k > cap) k = cap;
  memcpy(dst, tmp, k);
  dst[k] = 0;
}
static void replace(char* dst, size_t cap, const char* a, const char* b, long n, long pos) {
  char tmp[256];
  size_t la = strlen(a), lb = strlen(b);
  if (pos < 1) pos = 1;
  size_t p = (size_t)(pos - 1) > la ? la : (size_t)(pos - 1);
  size_t k = n < 0 ? 0 : ((size_t)n > la - p ? la - p : (size_t)n);
  memcpy(tmp, a, p);
  memcpy(tmp + p, b, lb);
  memcpy(tmp + p + lb, a + p + k, la - p - k);
  size_t total = la - k + lb;
  if (total > cap) total = cap;
  memcpy(dst, tmp, total);
  dst[total] = 0;
}
static long find(const char* a, const char* b) {
  const char* p = strstr(a, b);
  return p ? (long)(p - a) + 1 : 0;
}

int32_t c_stringfuncs(int32_t n) {
  int32_t total = 0;
  char s[81], t[81], tmp[81];
  for (int32_t i = 1; i <= n; ++i) {
    assign(s, 80, "conveyor belt 42 running");
    mid(t, 80, s, 4, 10);
    insert(t, 80, t, "-x-", 2);
    replace(t, 80, t, "YZ", 3, 1);
    total += (int32_t)find(s, "belt") + (int32_t)strlen(t);
    mid(tmp, 80, s, 5, 1);
    total += (int32_t)strlen(tmp);
    assign(tmp, 80, s);
    memmove(tmp + 1, tmp + 4, strlen(tmp + 4) + 1);   /* DELETE(s, 3, 2) */
    total += (int32_t)strlen(tmp);
  }
  return total;
}

#include <stdio.h>
#include <stdlib.h>
int32_t c_conversions(int32_t n) {
  int32_t total = 0;
  char s[81];
  for (int32_t i = 1; i <= n; ++i) {
    snprintf(s, sizeof s, "%d", i * 7 - 5000);
    total += (int32_t)strtol(s, NULL, 10) + (int32_t)strlen(s);
  }
  return total;
}
