#include <cstdio>
int main() { std::puts("deb: under construction"); return 0; }
