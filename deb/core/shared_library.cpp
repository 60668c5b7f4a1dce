#include "deb/core/shared_library.h"

#include <dlfcn.h>

namespace deb {

SharedLibrary::SharedLibrary(const char* soname) : soname_(soname) {
  handle_ = dlopen(soname, RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) {
    const char* why = dlerror();
    failure_ = why != nullptr ? why : soname_ + ": dlopen failed";
  }
}

void* SharedLibrary::Symbol(const char* name) const { return handle_ != nullptr ? dlsym(handle_, name) : nullptr; }

void* SharedLibrary::GlobalSymbol(const char* name) { return dlsym(RTLD_DEFAULT, name); }

}  // namespace deb
