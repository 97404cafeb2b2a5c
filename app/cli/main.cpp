#include <cstdio>
int main() { std::puts("octrace " OCTRACE_VERSION); return 0; }
