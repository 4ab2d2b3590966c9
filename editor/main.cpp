#include <cstdio>
int main() { std::puts("glint: placeholder"); return 0; }
