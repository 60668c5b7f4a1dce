// budget_rms BUDGET.yaml: loads the budget, evaluates it and prints the RMS of
// every output as "RMS<tab>NAME", with 17 significant digits (a double reads
// back exactly). Written as a user of the installed library would: deb/deb.h
// and the target deb::deb only.
#include <cstdio>
#include <exception>

#include "deb/deb.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s BUDGET.yaml\n", argv[0]);
    return 2;
  }
  try {
    const deb::Budget budget = deb::LoadBudgetFile(argv[1]);
    const deb::BudgetResult result = deb::Evaluate(budget);
    for (const deb::OutputResult& output : result.outputs) {
      std::printf("%.17g\t%s\n", output.rms(), output.name.c_str());
    }
  } catch (const deb::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
