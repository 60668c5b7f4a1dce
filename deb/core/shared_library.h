// Internal: not part of the public API.
// A shared library loaded at run time, and its symbols as typed pointers.
// deb loads its heavy optional libraries (matio, HDF5, libxlsxwriter, cairo
// with pango and librsvg) only when a file needs them: linked, they and the
// libraries under them cost milliseconds at every start of deb. Each is used
// by one module (mat_file, hdf5_file, xlsx_file, pdf_libraries), which lists
// the functions it calls and resolves them through this class, once.
#pragma once

#include <cstring>
#include <string>

namespace deb {

class SharedLibrary {
 public:
  // Loads `soname` (RTLD_NOW | RTLD_LOCAL). A library is never unloaded:
  // those deb loads keep process-wide state until exit.
  explicit SharedLibrary(const char* soname);

  bool loaded() const { return handle_ != nullptr; }
  const std::string& soname() const { return soname_; }
  // Why the library or a symbol could not be loaded (the first failure);
  // "" while all is well.
  const std::string& failure() const { return failure_; }
  // Whether the library defines `name` (no failure recorded if not).
  bool Has(const char* name) const { return Symbol(name) != nullptr; }

  // The function or variable `name` into `pointer` (a pointer of its type);
  // false, with the failure recorded, if the library is not loaded or lacks
  // it.
  template <class Pointer>
  bool Resolve(const char* name, Pointer& pointer) {
    return Assign(Symbol(name), name, pointer);
  }

  // A variable as the library's own code sees it. Where the process holds a
  // library with this symbol in its global scope, a program that refers to
  // the variable has its own copy (a copy relocation), which the library
  // uses and sets, leaving its own unset: symbols resolve to the first
  // definition in the global scope, for the library's code as for any. So
  // does this, and takes the library's own only where there is none (the
  // usual case: the library loaded here alone, locally).
  template <class Pointer>
  bool ResolveVariable(const char* name, Pointer& pointer) {
    void* const global = GlobalSymbol(name);
    return Assign(global != nullptr ? global : Symbol(name), name, pointer);
  }

 private:
  void* Symbol(const char* name) const;
  static void* GlobalSymbol(const char* name);

  template <class Pointer>
  bool Assign(void* symbol, const char* name, Pointer& pointer) {
    if (symbol == nullptr) {
      if (failure_.empty()) failure_ = soname_ + " has no symbol " + name;
      return false;
    }
    static_assert(sizeof pointer == sizeof symbol, "a symbol is held in a pointer");
    std::memcpy(&pointer, &symbol, sizeof pointer);
    return true;
  }

  void* handle_ = nullptr;
  std::string soname_;
  std::string failure_;
};

}  // namespace deb
