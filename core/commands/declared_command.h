// trispline::core::DeclaredCommand — a command whose parameters are one params struct P declared by a ParamSchema.
//
// The derived class C defines `static Schema declare();` (in its .cpp) and the effect (redo/undo, or build()
// for a SnapshotCommand); schema() builds that once, and parsing, to_json() and id() come from it, so the id, every
// field's name, default, range and help are written once. Register it with one line: `registry.add<C>();`.
// `Schema` is ParamSchema<P> and `P` the params struct, both named here, so C's .cpp writes
// `auto C::declare() -> Schema { return Schema("id", "summary").field("object", &P::object, {...}); }`.
// ObjectSnapshotCommand<C, P[, Base]> is the common case: a SnapshotCommand (VolumeSnapshotCommand for volumes) whose
// target is the params' `object` field.
#pragma once

#include <memory>
#include <utility>

#include "core/commands/snapshot_command.h"
#include "core/params/params.h"

namespace trispline::core {

template <class C, class ParamsT, class Base = Command>
class DeclaredCommand : public Base {
 public:
  using Params = ParamsT;
  using P = ParamsT;  // the short name the declare() bodies use
  using Schema = ParamSchema<ParamsT>;
  DeclaredCommand() = default;
  explicit DeclaredCommand(P p) : p_(std::move(p)) {}

  // The command's schema: C::declare(), built on first use.
  static const Schema& schema() {
    static const Schema s = C::declare();
    return s;
  }

  // Throws CommandError naming the bad field.
  static CommandPtr parse(const nlohmann::json& line, const CommandContext& ctx) {
    auto command = std::make_unique<C>();
    static_cast<DeclaredCommand&>(*command).p_ = C::schema().parse(line, ctx);
    return command;
  }
  std::string id() const override { return C::schema().id(); }
  nlohmann::json to_json() const override { return C::schema().to_json(p_); }
  const P& params() const { return p_; }

 protected:
  P p_;
};

// A declared snapshot command (SnapshotCommand for scene objects, VolumeSnapshotCommand for volumes) that changes the
// item named by P::object (a std::string).
template <class C, class P, class Base = SnapshotCommand>
class ObjectSnapshotCommand : public DeclaredCommand<C, P, Base> {
 public:
  ObjectSnapshotCommand() = default;
  explicit ObjectSnapshotCommand(P p) : DeclaredCommand<C, P, Base>(std::move(p)) {}

 protected:
  std::string target() const override { return this->p_.object; }
};

}  // namespace trispline::core
