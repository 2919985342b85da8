/* Checked parsing of command-line values for the sample programs: a bad value is reported
 * with the flag, the text and the accepted range, never silently read as 0. */
#ifndef VP_SAMPLE_CLI_VALUES_H
#define VP_SAMPLE_CLI_VALUES_H

/* Each returns 1 on success; on failure prints "PROGRAM: FLAG = 'TEXT': expected ..." and
 * leaves *out unchanged. */
int cliInt(const char* program, const char* flag, const char* text, int lo, int hi, int* out);
int cliDouble(const char* program, const char* flag, const char* text, double lo, double hi, double* out);
/* WIDTHxHEIGHT, each in [lo, hi]. */
int cliSize(const char* program, const char* flag, const char* text, int lo, int hi, int* width, int* height);
/* One of `count` words; *out = its index. */
int cliChoice(const char* program, const char* flag, const char* text, const char* const* choices, int count, int* out);

#endif
