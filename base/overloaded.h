#pragma once
// The sum types' idiom: std::visit(Overloaded{[](const A&) {...}, [](const B&) {...}}, value).

namespace omnicam {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;  // clang before 17 deduces no aggregate's arguments

}  // namespace omnicam
