// An outside program that finds stepzip with find_package and uses it.
#include <cstdio>
#include <vector>

#include <stepzip/stepzip.hpp>

int main() {
    std::vector<stepzip::Step> steps;
    stepzip::patent_forward(7, 3, 3 - 7, steps);
    stepzip::Chain chain;
    chain.steps = steps;
    auto codes = stepzip::to_freeman(chain);
    if (!codes || *codes != "0020020020") {
        std::puts("unexpected result");
        return 1;
    }
    std::printf("stepzip %s: %s\n", stepzip::version_string(), codes->c_str());
    return 0;
}
