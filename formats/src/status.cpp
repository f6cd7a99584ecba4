// The names of Status's codes (looptess/status.h).
#include "looptess/status.h"

namespace lt {

const char* toString(Status::Code code) {
    switch (code) {
    case Status::Ok: return "Ok";
    case Status::Usage: return "Usage";
    case Status::BadInput: return "BadInput";
    case Status::Unsupported: return "Unsupported";
    case Status::WriteFailed: return "WriteFailed";
    case Status::Internal: return "Internal";
    }
    return "Unknown";
}

}  // namespace lt
