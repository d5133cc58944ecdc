// trispline::core::DeclaredCommand — a command whose parameters are one params struct P declared by a ParamSchema.
//
// The derived class C defines `static Schema declare();` (in its .cpp) and the effect (redo/undo, or build()
// for a SnapshotCommand); schema() builds that once, and parsing, to_json(), id() and label() come from it, so the
// id, the History label, every field's name, default, range and help are written once. Register it with one line:
// `registry.add<C>();`. `Schema` is ParamSchema<P> and `P` the params struct, both named here, so C's .cpp writes `auto
// C::declare() -> Schema { return Schema("id", "summary").field("object", &P::object, {...}); }`.
// DeclaredSnapshotCommand<C, P, Base> is a declared SnapshotCommand (or VolumeSnapshotCommand, AddObjectCommand) whose
// failures without a field of their own blame the schema's failure_field(); ObjectSnapshotCommand<C, P[, Base]>, the
// common case, is one whose target is the params' `object` field.
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
  std::string label() const override { return C::schema().label(p_); }
  nlohmann::json to_json() const override { return C::schema().to_json(p_); }
  const P& params() const { return p_; }

 protected:
  P p_;
};

// A declared snapshot command (Base: SnapshotCommand, VolumeSnapshotCommand or AddObjectCommand): a failure of
// build() that names no field blames the schema's failure_field().
template <class C, class P, class Base>
class DeclaredSnapshotCommand : public DeclaredCommand<C, P, Base> {
 public:
  DeclaredSnapshotCommand() = default;
  explicit DeclaredSnapshotCommand(P p) : DeclaredCommand<C, P, Base>(std::move(p)) {}

 protected:
  std::string failure_field() const override { return C::schema().failure_field(); }
};

// A declared snapshot command that changes the item (object or volume) named by P::object (a std::string).
template <class C, class P, class Base = SnapshotCommand>
class ObjectSnapshotCommand : public DeclaredSnapshotCommand<C, P, Base> {
 public:
  ObjectSnapshotCommand() = default;
  explicit ObjectSnapshotCommand(P p) : DeclaredSnapshotCommand<C, P, Base>(std::move(p)) {}

 protected:
  std::string target() const override { return this->p_.object; }
};

}  // namespace trispline::core
