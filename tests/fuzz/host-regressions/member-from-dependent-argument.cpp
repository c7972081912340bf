template <typename T> struct Iter { T location; template <typename R> Iter(const R& rhs) : location(rhs.location) {} };
